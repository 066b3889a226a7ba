"""Internals shared by every subpackage: validation, atomic files, rng, progress."""
