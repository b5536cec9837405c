"""Skies and climate: the exterior light that glazing lets in (docs/daylight.md)."""
