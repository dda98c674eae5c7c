"""The supported platforms and Pythons install the lab, the book and Binder's environment from
wheels, every package pinned (issue 32, item 2).

``test_resolves_from_wheels`` runs course.wheels' dry runs against PyPI: one pip process per
platform and Python for lab, book and binder together, a few at a time in threads.  It needs
the network; without PyPI it fails, unless SHAPELAB_OFFLINE=1 says the machine is meant to be
offline, and then it skips.  The other tests are offline.
"""

from __future__ import annotations

import os
import re
import tomllib
from pathlib import Path

import pytest

from course import pins as course_pins
from course import wheels

ROOT = Path(__file__).resolve().parents[2]


def _minor(v: str) -> tuple[int, int]:
    major, minor = v.split(".")[:2]
    return int(major), int(minor)


@pytest.fixture(scope="module")
def results():
    if not wheels.pypi_reachable():
        if os.environ.get("SHAPELAB_OFFLINE") == "1":
            pytest.skip("PyPI is unreachable and SHAPELAB_OFFLINE=1: the wheel resolutions need the network")
        pytest.fail("PyPI is unreachable (set SHAPELAB_OFFLINE=1 to skip the wheel resolutions on an offline machine)")
    return wheels.resolve_all()


def test_resolves_from_wheels(results):
    """Each platform x CPython x {lab, book, binder} resolves with --only-binary=:all:, all pinned."""
    problems = []
    for r in results:
        if "+" in r.target and not r.ok:
            continue  # its targets were then resolved one by one and are reported below
        if not r.ok:
            problems.append(f"{r.label}: does not resolve\n{r.error}")
        elif unpinned := wheels.check_pinned(r):
            problems.append(f"{r.label}: not pinned by requirements/constraints.txt: {', '.join(unpinned)}")
    covered = {(r.platform, r.python) for r in results}
    assert covered == {(p, py) for p in wheels.PLATFORMS for py in wheels.PYTHONS}
    assert not problems, "\n\n".join(problems) + "\n\n" + wheels.table(results)


def test_markers_are_evaluated_for_the_target(results):
    """pip evaluates markers for the machine that runs it; the shim makes them the target's.  If a
    pip release stopped reading packaging's default_environment, Windows would lose pywinpty here."""
    for r in results:
        if r.ok and r.platform == "windows-amd64":
            assert {"pywinpty", "colorama"} <= set(r.installed), r.label
        if r.ok and r.platform.startswith("macos"):
            assert "appnope" in r.installed, r.label
        if r.ok and r.platform.startswith("linux"):
            assert not {"pywinpty", "colorama", "appnope"} & set(r.installed), r.label


def test_requirements_expand_self_references():
    lab = wheels.requirements("lab")
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert lab[: len(project["dependencies"])] == project["dependencies"]
    assert "MDAnalysis>=2.7" in lab and "jupyterlab>=4" in lab and "ipykernel>=6" in lab
    assert not [r for r in lab + wheels.requirements("book") if r.lower().startswith("shapelab")]
    assert "jupyter-book>=1,<2" in wheels.requirements("book")


def test_pip_sees_only_pypi_and_the_pins(monkeypatch):
    """The machine's pip.conf, PIP_FIND_LINKS and the like do not reach the dry runs."""
    monkeypatch.setenv("PIP_FIND_LINKS", "/opt/wheels")
    monkeypatch.setenv("PIP_CONSTRAINT", "/etc/xdg/pip/constraints.txt")
    env = wheels._env()
    assert env["PIP_CONFIG_FILE"] == os.devnull
    assert "PIP_FIND_LINKS" not in env and "PIP_CONSTRAINT" not in env
    platform = wheels.PLATFORMS["windows-amd64"]
    cmd = wheels.command(platform, "3.13", ("lab", "binder"), "report.json")
    assert cmd[cmd.index("--index-url") + 1] == "https://pypi.org/simple"
    assert cmd[cmd.index("--abi") + 1] == "cp313" and cmd[cmd.index("--python-version") + 1] == "3.13.0"
    assert cmd[cmd.index("-c") + 1] == str(wheels.CONSTRAINTS) and str(wheels.BINDER) in cmd
    env = platform.marker_env("3.13")
    assert (env["sys_platform"], env["os_name"], env["python_version"]) == ("win32", "nt", "3.13")


def test_every_platform_and_python_has_one_pin_per_package():
    """constraints.txt pins no package twice on any platform and Python (wheels.pins raises), numpy on all."""
    for platform in wheels.PLATFORMS.values():
        for python in wheels.PYTHONS:
            fixed = wheels.pins(platform, python)
            assert "numpy" in fixed and "jupyterlab" in fixed
    assert wheels.pins(wheels.PLATFORMS["windows-amd64"], "3.12")["pywinpty"]
    assert "pywinpty" not in wheels.pins(wheels.PLATFORMS["linux-x86_64"], "3.12")


def test_constraints_are_what_pins_writes(tmp_path):
    """constraints.txt is the freeze's lines merged with requirements/overrides.txt, not hand-edited."""
    lines = [line for line in wheels.CONSTRAINTS.read_text().splitlines() if line and not line.startswith("#")]
    overrides = course_pins.read_overrides(course_pins.OVERRIDES)
    freeze = tmp_path / "freeze.txt"
    freeze.write_text("\n".join(line for line in lines if "#" not in line) + "\n")
    assert course_pins.merge(course_pins._read(str(freeze)), overrides) == lines
    assert not course_pins.coverage_errors(course_pins._read(str(freeze)), overrides)


def test_supported_pythons_agree():
    """requires-python, the classifiers, ruff's target, README and course.wheels name one range."""
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text())
    project = pyproject["project"]
    low = _minor(re.fullmatch(r">=\s*(3\.\d+)", project["requires-python"]).group(1))
    classified = sorted(
        _minor(m.group(1))
        for c in project["classifiers"]
        if (m := re.fullmatch(r"Programming Language :: Python :: (3\.\d+)", c))
    )
    tested = sorted(_minor(v) for v in wheels.PYTHONS)
    assert classified == tested, "the version classifiers are the Pythons course.wheels resolves"
    assert classified == [(3, m) for m in range(classified[0][1], classified[-1][1] + 1)], "no gap"
    assert classified[0] == low
    assert pyproject["tool"]["ruff"]["target-version"] == f"py{low[0]}{low[1]}"
    readme = re.search(r"You need Python (3\.\d+) to (3\.\d+)", (ROOT / "README.md").read_text())
    assert readme, "README: 'You need Python 3.X to 3.Y'"
    assert (_minor(readme.group(1)), _minor(readme.group(2))) == (classified[0], classified[-1])
    runtime = (ROOT / "binder" / "runtime.txt").read_text().strip()
    assert _minor(runtime.removeprefix("python-")) in classified


def test_constraints_have_no_python_below_the_floor():
    """No pin is left for a Python that requires-python no longer admits (3.10's lines are gone)."""
    text = wheels.CONSTRAINTS.read_text()
    assert not re.search(r"python_version\s*(<|<=|==)\s*\"3\.10\"", text) and '< "3.11"' not in text
