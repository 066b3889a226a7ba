"""The studio in-process for the fuzz tests of its endpoints (no warm-up thread: quick, and nothing beside the test)."""

from __future__ import annotations

import pytest


@pytest.fixture(scope="module")
def studio(tmp_path_factory):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        from starlette.testclient import TestClient

    from voxfab.studio import Settings, create_app

    folder = tmp_path_factory.mktemp("studio")
    app = create_app(Settings(repo=folder / "repo.sqlite", hosts=frozenset({"testserver"}), work=folder / "work",
                              warm_up=False))
    with TestClient(app) as client:
        yield client
