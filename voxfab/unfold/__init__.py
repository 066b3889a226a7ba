"""Nets: single-piece edge unfoldings of voxel surfaces, and their validator."""

from ._net import NET_FORMAT, Net

__all__ = ["NET_FORMAT", "Net"]
