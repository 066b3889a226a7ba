"""The studio's routes, one module per thing they serve, each with ``routes(session)`` giving its Starlette routes.

* :mod:`.page`: the page, its files, and what it asks at start (``/``, ``/static/...``, ``/api/info``,
  ``/api/initial``);
* :mod:`.draw`: a drawn shape's voxels, recipe and animation (``/api/preview``, ``/api/recipe``,
  ``/api/animate``);
* :mod:`.edit`: the facts of an edited shape (``/api/check``);
* :mod:`.keep`: the repository (``/api/repo``, ``/api/repo/shape``, ``/api/repo/thumb``);
* :mod:`.net`: nets to choose from, edit and fit on a sheet (``/api/nets``, ``/api/nets/edit``, ``/api/fits``);
* :mod:`.make`: the fabrication files (``/api/make``);
* :mod:`.jobs`: the jobs those start, and their files (``/api/jobs/...``, ``/api/files/...``);
* :mod:`.paint`: colours, joining parts, the shape as a file (``/api/palette``, ``/api/paint/fit``,
  ``/api/join``, ``/api/shape/file``, ``/api/shape/open``).

A route is a module function ``async def name(session, request)`` returning JSON-ready
data or a response; :meth:`.._session.Session.api` binds it to the session.
"""
