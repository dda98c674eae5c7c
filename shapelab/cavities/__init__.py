"""Voids, pockets and tunnels of a union of balls (Notes §23.1, "Voids and pockets").

Notes §23.1 define a *void* as a bounded connected component of
:math:`\\mathbb{R}^3 \\setminus \\bigcup_i B_i` and, through the growth model, a *pocket*
as a dent of the surface that "will produce a void in the life time of the filtration";
a *groove* likewise turns into a *tunnel*.  This module computes all of them from the
α-filtration (:func:`shapelab.alpha_filtration`), in 2D (holes and dents of unions of
disks) and in 3D.

Where the computation lives
---------------------------
* **Complement.**  The dual complex :math:`K_\\tau` lies inside the union
  :math:`U_\\tau` of the grown balls and :math:`U_\\tau` deformation-retracts onto it
  (Edelsbrunner 1995), so by Alexander duality the components of
  :math:`\\mathbb{R}^d \\setminus U_\\tau` correspond one to one to the components of
  :math:`\\mathbb{R}^d \\setminus |K_\\tau|`: the top simplices of the regular
  triangulation not in :math:`K_\\tau`, glued along :math:`(d-1)`-simplices not in
  :math:`K_\\tau`, plus the outside.  A void is such a component that avoids the
  outside; its *cells* are those top simplices and the free space of the void is
  exactly the part of those cells that no grown ball covers.
* **Merge tree.**  Running τ backwards the complement only grows, so one union–find
  pass in reverse filtration order (the dual :math:`H_0`, see
  :mod:`shapelab.persistence`) records when every void is sealed (``born``) and filled
  (``dies``), and which cells it holds at every moment.
* **Pockets** (growth-model definition of the notes).  A pocket at τ is a region of
  the complement that is still connected to the outside at τ but is sealed off into a
  void at a later :math:`\\tau' > \\tau` (``closes_at``), filled at ``fills_at``.  Its
  cells are the cells of that void at the moment it closes; its *mouth* at τ is the
  set of :math:`(d-1)`-simplices not in :math:`K_\\tau` through which those cells open
  to the outside: each has one side in the pocket and the other in the component of
  :math:`\\infty` of the complement once the pocket's cells are removed.  A face on
  the pocket's boundary that leads into a crevice of its own wall (free cells reachable
  from the outside only through the pocket) is no opening (:func:`pockets`, Notes).
  A dent whose cells fill before its mouth closes never becomes a void and is no
  pocket (Figure 23.2, right).  Pockets nest: a pocket's cells can contain the cells
  of a pocket that closes later (the "pocket hierarchy").
* **Tunnels** are the :math:`H_1` classes alive at τ in 3D (birth ≤ τ < death), each
  with a representative cycle taken from the reduced boundary matrix: the cycle born
  at ``birth`` that becomes a boundary at ``death``.  Grooves (:func:`grooves`) are the
  :math:`H_1` classes born after τ.

Volumes
-------
``Void.volume`` and ``Pocket.volume`` (the free space of a void or pocket) come from
:mod:`shapelab.cavities.freespace`: fractional inclusion–exclusion over the void's cells, and
the exact power-cell decomposition for pockets.

Modules, one concept each
-------------------------
``complement`` (the dual graph of the complement of :math:`K_\\tau`, its components
and merge tree), ``void``, ``pocket`` (the growth model), ``mouths`` (a region's
openings to the outside), ``tunnel`` (tunnels, grooves, the channel profile),
``flow`` (Edelsbrunner's discrete flow and its pockets), ``freespace`` (exact free
area and volume), ``cavity`` (the :class:`Cavity` protocol).  The machinery (the
merge tree's union–find, the certified mouth search, the flow's exact signs, the
free-space integration) is in the private ``shapelab._engine``; where a result
depends on it, ``precision="exact"`` (the default) runs it and ``precision="fast"``
the plain path written here.
"""

from __future__ import annotations

from .._toolkit.lazy import attach

#: public name -> the submodule that defines it (imported on first access)
_EXPORTS = {
    "Cavity": "cavity",
    "Void": "void",
    "voids": "void",
    "Pocket": "pocket",
    "pockets": "pocket",
    "growth_pockets": "pocket",
    "Tunnel": "tunnel",
    "tunnels": "tunnel",
    "grooves": "tunnel",
    "ChannelProfile": "tunnel",
    "channel_profile": "tunnel",
    "DiscreteFlow": "flow",
    "FlowPocket": "flow",
    "discrete_flow": "flow",
    "flow_pockets": "flow",
    "flow_side_exact": "flow",
    "MeasuredRegion": "mouths",
    "mouth": "mouths",
    "complement_labels": "complement",
    "sealed_at": "complement",
    "cells_when_sealed": "complement",
    "merge_tree": "complement",
    "lining_of": "complement",
    "vertex_values": "complement",
    "void_measure": "freespace",
    "free_measure": "freespace",
    "free_space": "freespace",
    "free_area": "freespace",
    "free_points": "freespace",
    "FreeSpace": "freespace",
}
_SUBMODULES = {"cavity", "complement", "void", "pocket", "mouths", "tunnel", "flow", "freespace"}

__all__ = [
    "Cavity",
    "Void",
    "Pocket",
    "Tunnel",
    "voids",
    "pockets",
    "tunnels",
    "grooves",
    "ChannelProfile",
    "channel_profile",
]

__getattr__, __dir__ = attach(__name__, _EXPORTS, _SUBMODULES, eager=__all__)
