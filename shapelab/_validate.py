"""Compatibility shim: the validators moved to :mod:`shapelab._toolkit.validate`.

Kept for the modules not yet switched (hausdorff, critical, registration, quaternion,
datasets); new code imports from ``._toolkit.validate``.
"""

from ._toolkit.validate import *  # noqa: F401,F403
from ._toolkit.validate import __all__  # noqa: F401
from ._toolkit.validate import as_float_array as _as_float_array  # noqa: F401
from ._toolkit.validate import check_finite as _check_finite  # noqa: F401
