"""Scenes: geometry, materials, patches, emitter zones, built-in scenes, drawn zones and
model import.
"""
