"""Error types the engine raises for bad user input.

Every error a user can cause (a bad file, a bad number, a missing group) is a
``LightInvError`` with a message that says what is wrong, where, and what to do.
Anything else escaping the engine is a bug.
"""


class LightInvError(ValueError):
    """Base class of all user-facing errors."""


class SceneError(LightInvError):
    """A scene, surface, material or emitter zone is invalid."""


class ObjImportError(SceneError):
    """An OBJ/MTL file or its materials mapping cannot be imported."""


class DesignError(LightInvError):
    """The design specification is invalid (bad value, unknown name, contradictory rules)."""


class CancelledError(LightInvError):
    """Long work was cancelled by the caller (the cancel callback returned True)."""


class PhotometryError(LightInvError):
    """A photometric file (IES LM-63, EULUMDAT) or the luminaire catalogue cannot be read."""


class OutputError(LightInvError):
    """An output file cannot be written (checked before long work, reported after it)."""
