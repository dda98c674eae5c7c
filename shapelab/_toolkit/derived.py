"""Results derived from an object, kept on it (the Filtration owns what is computed
from it): one helper, so that the modules computing from a filtration need not import
the filtration module for it."""

from __future__ import annotations

__all__ = ["KeepsDerived", "derived"]


class KeepsDerived:
    """The base of :class:`shapelab.Balls` and :class:`shapelab.Filtration`: immutable
    objects that keep what is derived from them (in their ``_derived`` dict), so that
    it lives exactly as long as they do, with no module-level cache."""

    __slots__ = ()

    def derived(self, key: str, build):
        """A result derived from this object, built on first use and kept on it.

        One filtration, many questions (Betti numbers, persistence, voids, pockets,
        tunnels): their modules keep intermediate results on the filtration; and every
        function of a filtration takes Balls or a Filtration, the Balls filtered once
        and the filtration kept on them (Balls do not pickle or copy it; a Filtration does).

        Parameters
        ----------
        key : str
            Names the result (e.g. ``"topology.summary"``); one key, one builder.
        build : callable
            ``build(self)`` computes it.  Results must be treated as read-only: every
            later caller gets the same object.

        Returns
        -------
        object
            ``build(self)``, computed once per object (``dataclasses.replace(F)`` is a
            filtration with nothing derived yet, to time a computation from scratch).

        See Also
        --------
        shapelab.alpha_filtration
            The filtration that Balls keep.
        """
        cache = self._derived
        try:
            return cache[key]
        except KeyError:
            return cache.setdefault(key, build(self))


def derived(F, key: str, build):
    """``F.derived(key, build)`` (:meth:`shapelab.filtration.Filtration.derived`): the
    result kept on ``F``.  Any other object with the filtration's accessors (an adapter
    over another library's complex, in the tests) keeps nothing: ``build(F)`` each time."""
    get = getattr(F, "derived", None)
    return get(key, build) if callable(get) else build(F)
