"""Results derived from an object, kept on it (the Filtration owns what is computed
from it): one helper, so that the modules computing from a filtration need not import
the filtration module for it."""

from __future__ import annotations

__all__ = ["derived"]


def derived(F, key: str, build):
    """``F.derived(key, build)`` (:meth:`shapelab.filtration.Filtration.derived`): the
    result kept on ``F``.  Any other object with the filtration's accessors (an adapter
    over another library's complex, in the tests) keeps nothing: ``build(F)`` each time."""
    get = getattr(F, "derived", None)
    return get(key, build) if callable(get) else build(F)
