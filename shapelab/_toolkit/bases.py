"""Base types named in the bottom layer, so that it can recognise the objects of the
layers above without importing them (no upward import, no cycle).

:class:`shapelab.Balls` derives from :class:`BallsBase`; :func:`check_balls` in
:mod:`shapelab._toolkit.validate` tests ``isinstance(x, BallsBase)``.
"""

from __future__ import annotations

import abc

__all__ = ["BallsBase"]


class BallsBase(abc.ABC):  # noqa: B024 (a marker: no abstract method is needed)
    """The base of :class:`shapelab.Balls` (and of nothing else)."""

    __slots__ = ()
