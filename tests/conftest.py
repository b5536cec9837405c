"""Shared fixtures: small built-in scenes and their form factors, computed once per session."""

from __future__ import annotations

import os

import pytest

from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.formfactors import form_factor_matrix


@pytest.fixture(scope="session")
def cornell_patches():
    """The cornell box at its default resolution (~1,100 patches)."""
    return mesh_patches(builtin_scene("cornell"))


@pytest.fixture(scope="session")
def cornell_F(cornell_patches):
    """Form factors of the cornell box with 1,024 rays per patch."""
    return form_factor_matrix(cornell_patches, 1024, seed=1)


@pytest.fixture(scope="session", autouse=True)
def private_operator_cache(tmp_path_factory):
    """Operators built by the tests go to a temporary cache, never the user's; so do
    the window's autosaves."""
    saved = {k: os.environ.get(k) for k in ("LIGHTINV_CACHE_DIR", "LIGHTINV_AUTOSAVE_DIR")}
    os.environ["LIGHTINV_CACHE_DIR"] = str(tmp_path_factory.mktemp("operator-cache"))
    os.environ["LIGHTINV_AUTOSAVE_DIR"] = str(tmp_path_factory.mktemp("autosave"))
    yield
    for key, old in saved.items():
        if old is None:
            os.environ.pop(key, None)
        else:
            os.environ[key] = old


def pytest_collection_modifyitems(session, config, items):
    """The modules holding slow tests first, each kept whole (its module fixtures built
    once): with four workers on two cores, long tests left to the end of the queue ran
    alone while the other workers had nothing left (the longest-first rule)."""
    slow = {item.module.__name__ for item in items if item.get_closest_marker("slow")}
    items.sort(key=lambda item: item.module.__name__ not in slow)
