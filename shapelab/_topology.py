"""Moved to :mod:`shapelab._engine.persistence` (issue 33); kept for the modules that
still import it from here (``filtration``, ``cavities``, ``flow``, ``_pockets``)."""

from ._engine.persistence import *  # noqa: F401,F403
from ._engine.persistence import __all__  # noqa: F401
