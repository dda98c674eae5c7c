"""shapelab.io.ReadOptions: the readers' keywords, checked once (issue 33).

Every reader takes the same keywords; one check gives the same message whichever
reader is called, and the widths of ``chain=`` and ``hetatm=`` names follow the format.
"""

from __future__ import annotations

import inspect

import pytest

from shapelab.datasets import structure_path
from shapelab.io import ReadOptions, read_pdb, read_structure
from shapelab.io._bcif import read_bcif
from shapelab.io._mmcif import read_mmcif

KEYWORDS = ["probe", "default_radius", "model", "chain", "hetatm", "water", "hydrogens", "radii", "max_bytes"]


@pytest.mark.parametrize("reader", [read_pdb, read_structure])
def test_the_public_signatures_keep_their_keywords(reader):
    params = inspect.signature(reader).parameters
    assert [k for k in params if k in KEYWORDS] == KEYWORDS
    assert [params[k].default for k in KEYWORDS] == [0.0, None, None, None, True, False, False, None, 256 * 2**20]


@pytest.mark.parametrize(
    "kwargs, exc, match",
    [
        ({"probe": -1.0}, ValueError, "probe"),
        ({"default_radius": 0.0}, ValueError, "default_radius"),
        ({"model": True}, TypeError, "model must be an int, got bool"),
        ({"hetatm": "LONGER"}, ValueError, "hetatm must hold strings of at most"),
        ({"water": 1}, TypeError, "water must be a bool, got int"),
        ({"hydrogens": "yes"}, TypeError, "hydrogens must be a bool, got str"),
        ({"radii": 3}, TypeError, "radii must be a mapping"),
        ({"max_bytes": 0}, ValueError, "max_bytes"),
    ],
)
def test_one_check_for_every_reader(tmp_path, kwargs, exc, match):
    pdb = structure_path("1hvr")
    with pytest.raises(exc, match=match):
        read_pdb(pdb, **kwargs)
    with pytest.raises(exc, match=match):
        read_structure(pdb, **kwargs)
    for reader, fmt in ((read_mmcif, "mmcif"), (read_bcif, "bcif")):
        with pytest.raises(exc, match=match):
            reader(tmp_path / f"x.{fmt}", **kwargs)  # checked before the file is opened
        with pytest.raises(exc, match=match):
            ReadOptions.checked(tmp_path / f"x.{fmt}", fmt, **kwargs)


def test_name_widths_follow_the_format():
    with pytest.raises(ValueError, match="at most 2 characters, got 'ABC'"):
        ReadOptions.checked("x.pdb", "pdb", chain="ABC")
    assert ReadOptions.checked("x.cif", "mmcif", chain="ABC").chains_wanted == frozenset({"ABC"})
    with pytest.raises(ValueError, match="at most 4 characters"):
        ReadOptions.checked("x.cif", "mmcif", chain="ABCDE")
    assert ReadOptions.checked("x.cif", "mmcif", hetatm={"A1B2C"}).het_keep == frozenset({"A1B2C"})


def test_options_are_frozen_and_given_once():
    o = ReadOptions.checked("x.pdb", "pdb")
    with pytest.raises(AttributeError):
        o.probe = 1.0
    with pytest.raises(TypeError, match="not both"):
        read_mmcif("x.cif", o, probe=1.0)


def test_the_options_read_what_the_keywords_read():
    path = structure_path("1hvr")
    a = read_pdb(path, chain="A", hetatm={"CSO"}, probe=1.4)
    b = read_structure(path, chain="A", hetatm={"CSO"}, probe=1.4)
    assert len(a) == len(b) == 757
    assert (a.balls.centers == b.balls.centers).all() and (a.balls.radii == b.balls.radii).all()
