"""Shape makers: k-flake digitization, surfaces of revolution, swept tubes, focal shapes."""

from ._makers import MAKERS, available_makers, get_maker

__all__ = ["MAKERS", "available_makers", "get_maker"]
