"""The light model: the one place where a design state becomes light.

``LightModel`` (model.py) turns sources and a daylight condition into the light field
(``LightField``, field.py) or, for the optimizer, batches of illuminance at chosen
receivers; intentions.py judges lighting intentions on either.
"""

from lightinv_core.light.field import IntentionResult, LightField
from lightinv_core.light.intentions import FEASIBILITY_TOL, BoundCheck, intention_patches
from lightinv_core.light.model import LightModel, Receivers

__all__ = [
    "FEASIBILITY_TOL",
    "BoundCheck",
    "IntentionResult",
    "LightField",
    "LightModel",
    "Receivers",
    "intention_patches",
]
