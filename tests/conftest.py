"""Shared test settings: hypothesis profiles sized for the 2-core CI machine."""

from hypothesis import HealthCheck, settings

settings.register_profile(
    "voxfab", max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow]
)
settings.load_profile("voxfab")
