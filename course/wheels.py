"""Resolve the course's environments for every supported platform and Python from wheels alone.

    python -m course.wheels [--platform NAME] [--python X.Y[.Z]] [--target lab|book|binder] [--jobs N] [--separate]

A student runs ``pip install -c requirements/constraints.txt -e ".[lab]"`` (or ``.[book]``,
or repo2docker's ``binder/requirements.txt``) on Linux, macOS or Windows with CPython 3.11
to 3.14.  Each (platform, Python) here is one ``pip install --dry-run --report
--only-binary=:all:`` of the three targets together for that platform's wheel tags (each
target alone when that fails, or with ``--separate``; see ``resolve_all``), so a pin
without a wheel for some student shows up as a failed resolution, and ``check_pinned``
says which installed package the pins do not fix.  The options repeat.  It prints a
table; tests/course/test_wheels.py asserts it.

Two things make the dry run say what a student's machine would do:

* pip evaluates environment markers (``sys_platform == "win32"``, ``python_version >=
  "3.13"``, ...) against the interpreter that runs it, not the ``--platform`` and
  ``--python-version`` it was given, so Windows' ``pywinpty`` or macOS's ``appnope`` would
  be missed.  ``_SHIM`` runs pip with packaging's marker environment replaced by the
  target's (``Platform.marker_env``).
* The machine's pip configuration (local find-links, extra indexes, a global constraint
  file) is left out: ``PIP_CONFIG_FILE`` is the null device, no other ``PIP_*`` variable
  but the certificate and timeout is passed on, and the index is PyPI's, so only PyPI and
  the project's pins count.

The local project itself is not a wheel (``--only-binary=:all:`` refuses to build it), so
``requirements`` reads ``[project.dependencies]`` and the extras from pyproject.toml,
expands ``shapelab[...]`` self-references, and resolves those requirements.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time
import tomllib
import urllib.request
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CONSTRAINTS = ROOT / "requirements" / "constraints.txt"
BINDER = ROOT / "binder" / "requirements.txt"
INDEX = "https://pypi.org/simple"

PYTHONS = ("3.11", "3.12", "3.13", "3.14")
TARGETS = ("lab", "book", "binder")


def _manylinux(arch: str, glibc: int = 28) -> list[str]:
    """Every manylinux tag a glibc 2.``glibc`` machine installs, newest first, with the legacy aliases."""
    tags = [f"manylinux_2_{minor}_{arch}" for minor in range(glibc, 16, -1)]
    return (
        tags + [f"manylinux2014_{arch}"] + ([f"manylinux2010_{arch}", f"manylinux1_{arch}"] if arch == "x86_64" else [])
    )


@dataclass(frozen=True)
class Platform:
    name: str
    tags: tuple[str, ...]  # pip's --platform, each given once (pip expands macosx_* to the older releases itself)
    sys_platform: str
    platform_system: str
    platform_machine: str
    os_name: str = "posix"
    note: str = ""

    def marker_env(self, python: str) -> dict[str, str]:
        """PEP 508's marker variables on this platform under CPython ``python``."""
        return {
            "implementation_name": "cpython",
            "implementation_version": _full(python),
            "os_name": self.os_name,
            "platform_machine": self.platform_machine,
            "platform_python_implementation": "CPython",
            "platform_release": "",
            "platform_system": self.platform_system,
            "platform_version": "",
            "python_full_version": _full(python),
            "python_version": ".".join(python.split(".")[:2]),
            "sys_platform": self.sys_platform,
        }


# The oldest systems the course supports (CONTRIBUTING.md, "Pinned versions"): glibc 2.28 (RHEL/Alma 8,
# Debian 10; Ubuntu 20.04 has 2.31), macOS 12 (Monterey) on Apple silicon and on Intel
# (SciPy's arm64 wheels and pyarrow's need 12; every Apple-silicon Mac and most Intel Macs
# from 2015 on run it), Windows 10/11 on x86-64.
PLATFORMS = {
    p.name: p
    for p in (
        Platform("linux-x86_64", tuple(_manylinux("x86_64")), "linux", "Linux", "x86_64", note="glibc >= 2.28"),
        Platform("linux-aarch64", tuple(_manylinux("aarch64")), "linux", "Linux", "aarch64", note="glibc >= 2.28"),
        Platform("macos-arm64", ("macosx_12_0_arm64",), "darwin", "Darwin", "arm64", note="macOS >= 12"),
        Platform("macos-x86_64", ("macosx_12_0_x86_64",), "darwin", "Darwin", "x86_64", note="macOS >= 12"),
        Platform("windows-amd64", ("win_amd64",), "win32", "Windows", "AMD64", os_name="nt", note="64-bit"),
    )
}

# pip's main with packaging's marker environment replaced by the target's (argv[1], JSON).
_SHIM = """\
import json, sys
import pip._vendor.packaging.markers as markers
target = json.loads(sys.argv.pop(1))
markers.default_environment = lambda: dict(target)
from pip._internal.cli.main import main
sys.exit(main(sys.argv[1:]))
"""


def _full(python: str) -> str:
    """``3.11`` -> ``3.11.0``: a bare minor version stands for its first release."""
    return python if python.count(".") == 2 else f"{python}.0"


def _canonical(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def requirements(extra: str, pyproject: Path = ROOT / "pyproject.toml") -> list[str]:
    """The requirements of ``shapelab[extra]``: its dependencies and the extra's, self-references expanded."""
    project = tomllib.loads(pyproject.read_text())["project"]
    name, extras = _canonical(project["name"]), project.get("optional-dependencies", {})
    out, seen = list(project.get("dependencies", [])), set()

    def expand(e: str) -> None:
        if e in seen:
            return
        if e not in extras:
            raise KeyError(f"pyproject.toml has no extra {e!r}")
        seen.add(e)
        for req in extras[e]:
            m = re.match(r"\s*([A-Za-z0-9._-]+)\s*(?:\[([^\]]*)\])?\s*(.*)$", req)
            if m and _canonical(m.group(1)) == name:
                if m.group(3).strip():
                    raise ValueError(f"a self-reference with a version or marker is not expanded: {req!r}")
                for sub in m.group(2).split(","):
                    expand(sub.strip())
            elif req not in out:
                out.append(req)

    expand(extra)
    return out


@dataclass
class Result:
    platform: str
    python: str
    target: str
    ok: bool
    seconds: float
    installed: dict[str, str] = field(default_factory=dict)  # canonical name -> version
    error: str = ""

    @property
    def label(self) -> str:
        return f"{self.platform} / CPython {self.python} / {self.target}"


def _env() -> dict[str, str]:
    keep = {"PIP_CERT", "PIP_CLIENT_CERT", "PIP_DEFAULT_TIMEOUT"}
    env = {k: v for k, v in os.environ.items() if not k.startswith("PIP_") or k in keep}
    env["PIP_CONFIG_FILE"] = os.devnull  # no global, user or site pip.conf: no find-links, extra index, constraint
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    return env


def command(platform: Platform, python: str, targets: tuple[str, ...], report: str) -> list[str]:
    """The pip command line (after the shim) resolving ``targets`` together, its JSON report written to ``report``."""
    nodot = "".join(python.split(".")[:2])
    cmd = ["install", "--dry-run", "--ignore-installed", "--only-binary=:all:"]
    cmd += ["--report", report, "--index-url", INDEX, "--no-input", "--progress-bar", "off"]
    for tag in platform.tags:
        cmd += ["--platform", tag]
    cmd += ["--python-version", _full(python), "--implementation", "cp", "--abi", f"cp{nodot}"]
    cmd += ["-c", str(CONSTRAINTS)]
    for target in targets:
        if target == "binder":
            cmd += ["-r", str(BINDER)]  # with its own -c ../requirements/constraints.txt, the same file
        else:
            cmd += [req for req in requirements(target) if req not in cmd]
    return cmd


def resolve(
    platform: Platform, python: str, targets: tuple[str, ...], *, pip_python: str = sys.executable, timeout: float = 900
) -> Result:
    """One dry run of ``targets`` together; ``installed`` maps each package pip would install to its version."""
    target = "+".join(targets)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="shapelab-wheels-") as tmp:
        report_path = Path(tmp) / "report.json"
        argv = [pip_python, "-c", _SHIM, json.dumps(platform.marker_env(python))]
        argv += command(platform, python, targets, str(report_path))
        try:
            proc = subprocess.run(argv, capture_output=True, text=True, env=_env(), cwd=ROOT, timeout=timeout)
        except subprocess.TimeoutExpired as exc:
            return Result(platform.name, python, target, False, time.perf_counter() - start, error=f"timed out: {exc}")
        seconds = time.perf_counter() - start
        if proc.returncode != 0 or not report_path.exists():
            return Result(platform.name, python, target, False, seconds, error=_pip_error(proc.stdout + proc.stderr))
        report = json.loads(report_path.read_text())
    installed = {
        _canonical(item["metadata"]["name"]): item["metadata"]["version"] for item in report.get("install", [])
    }
    return Result(platform.name, python, target, True, seconds, installed=installed)


def _pip_error(stderr: str) -> str:
    """pip's message without its long tail of hints; the whole text if nothing is recognised."""
    lines = [line for line in stderr.splitlines() if line.strip() and not line.startswith(_NOISE)]
    for n, line in enumerate(lines):
        if line.startswith("ERROR") or "conflict is caused by" in line:
            return "\n".join(lines[n : n + 30])
    return "\n".join(lines[-30:])


_NOISE = (
    "Collecting ",
    "Requirement already",
    "Using cached",
    "Downloading ",
    "  Using cached",
    "  Downloading ",
    "Looking in indexes",
    "  Link requires",
    "Would install",
    "  Obtaining",
)


def pins(platform: Platform, python: str, constraints: Path = CONSTRAINTS) -> dict[str, str]:
    """The versions constraints.txt fixes on this platform and Python (lines whose marker holds)."""
    from packaging.requirements import Requirement

    env = platform.marker_env(python)
    out = {}
    for n, line in enumerate(constraints.read_text().splitlines(), 1):
        line = line.split("#")[0].strip()
        if not line:
            continue
        req = Requirement(line)
        if req.marker is not None and not req.marker.evaluate(env):
            continue
        (spec,) = req.specifier  # name==version only
        name = _canonical(req.name)
        if name in out:
            raise ValueError(f"{constraints.name}:{n}: {req.name} pinned twice for {platform.name}, CPython {python}")
        out[name] = spec.version
    return out


def check_pinned(result: Result, constraints: Path = CONSTRAINTS) -> list[str]:
    """The packages of a resolution that constraints.txt does not pin here, or pins to another version."""
    fixed = pins(PLATFORMS[result.platform], result.python, constraints)
    return sorted(
        f"{name}=={version}" + (f" (pinned {fixed[name]})" if name in fixed else " (not pinned)")
        for name, version in result.installed.items()
        if fixed.get(name) != version
    )


def pypi_reachable(timeout: float = 10) -> bool:
    try:
        with urllib.request.urlopen(f"{INDEX}/pip/", timeout=timeout) as response:
            return response.status == 200
    except OSError:
        return False


def resolve_all(platforms=None, pythons=PYTHONS, targets=TARGETS, jobs: int = 6, together: bool = True) -> list[Result]:
    """Every (platform, Python, target), ``jobs`` pip processes at a time.

    With ``together`` the targets of one platform and Python are resolved in one pip run
    (a third of the work: most of pip's time goes to reading index pages), and only when
    that fails each target alone, to say which.  One run proves each: when every package
    of the joint resolution is pinned (``check_pinned``), a target's own resolution can
    only be the joint one restricted to its dependencies, since each pinned package has one
    candidate and the joint solution already satisfies all their requirements.
    """
    platforms = [PLATFORMS[p] for p in (platforms or PLATFORMS)]
    if together and len(targets) > 1:
        combos = [(p, py, tuple(targets)) for p in platforms for py in pythons]
    else:
        combos = [(p, py, (t,)) for p in platforms for py in pythons for t in targets]

    def run(combo) -> list[Result]:
        result = resolve(*combo)
        if result.ok or len(combo[2]) == 1:
            return [result]
        return [result] + [resolve(combo[0], combo[1], (t,)) for t in combo[2]]

    with ThreadPoolExecutor(max_workers=jobs) as pool:
        return [r for rs in pool.map(run, combos) for r in rs]


def table(results: list[Result]) -> str:
    """Platform rows, one column per Python: ``ok``, or the targets that do not resolve (``FAIL``) or not pinned."""
    pythons = sorted({r.python for r in results}, key=lambda v: tuple(map(int, v.split("."))))
    by: dict[tuple[str, str], list[Result]] = {}
    for r in results:
        by.setdefault((r.platform, r.python), []).append(r)
    rows = ["| platform | " + " | ".join(f"CPython {py}" for py in pythons) + " |"]
    rows.append("| --- |" + " --- |" * len(pythons))
    for name in dict.fromkeys(r.platform for r in results):
        cells = []
        for py in pythons:
            rs = by.get((name, py), [])
            single = [r for r in rs if "+" not in r.target] or rs  # a joint run that failed is followed by its parts
            fail = [r.target for r in single if not r.ok]
            unpinned = [r.target for r in single if r.ok and check_pinned(r)]
            cell = ("FAIL " + ", ".join(fail) if fail else "") + ("; " if fail and unpinned else "")
            cell += "not pinned " + ", ".join(unpinned) if unpinned else ""
            cells.append(cell or ("ok" if rs else ""))
        rows.append(f"| {name} ({PLATFORMS[name].note}) | " + " | ".join(cells) + " |")
    return "\n".join(rows)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m course.wheels", description=__doc__.split("\n\n")[0])
    parser.add_argument("--platform", action="append", choices=sorted(PLATFORMS))
    parser.add_argument("--python", action="append")
    parser.add_argument("--target", action="append", choices=TARGETS)
    parser.add_argument("--jobs", type=int, default=6, help="pip processes at a time (default 6)")
    parser.add_argument(
        "--separate", action="store_true", help="one pip run per target, not one per platform and Python"
    )
    args = parser.parse_args(argv)
    start = time.perf_counter()
    pythons, targets = tuple(args.python or PYTHONS), tuple(args.target or TARGETS)
    results = resolve_all(args.platform, pythons, targets, args.jobs, together=not args.separate)
    failed = 0
    for r in results:
        unpinned = check_pinned(r) if r.ok else []
        if not r.ok or unpinned:
            failed += 1
            print(f"--- {r.label}: {'not pinned: ' + ', '.join(unpinned) if r.ok else 'does not resolve'}")
            if r.error:
                print(r.error)
    print(table(results))
    n = len(results)
    print(f"{n - failed}/{n} pip runs resolve with every package pinned, {time.perf_counter() - start:.0f} s")
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
