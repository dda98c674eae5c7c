"""The platform promises of issue #2: the lab launcher's security, the book config's
offline wiring, and the pins."""

import re
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]


def _lab():
    import course.lab

    return course.lab


def test_lab_binds_loopback_with_a_token():
    cmd = _lab().build_command("abc123", "8888", as_root=False)
    assert "--ServerApp.ip=127.0.0.1" in cmd
    assert "--IdentityProvider.token=abc123" in cmd
    assert "--allow-root" not in cmd


def test_lab_allows_root_only_as_root():
    assert "--allow-root" in _lab().build_command("t", "8888", as_root=True)


def test_lab_refuses_an_empty_token():
    with pytest.raises(ValueError, match="token"):
        _lab().build_command("", "8888", as_root=False)


def test_book_serves_its_javascript_locally():
    cfg = yaml.safe_load((ROOT / "book" / "_config.yml").read_text())
    sphinx = cfg["sphinx"]["config"]
    assert "://" not in sphinx["mathjax_path"]
    assert all("://" not in url for url in sphinx["nb_ipywidgets_js"])
    assert cfg["execute"]["execute_notebooks"] == "off"
    # nothing under _static: Jupyter Book would inject every .js there into every page
    assert not list((ROOT / "book").glob("_static/**/*.js"))


def test_toc_lists_every_lesson():
    toc = (ROOT / "book" / "_toc.yml").read_text()
    for nb in sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb")):
        assert f"lessons/{nb.stem}" in toc, f"{nb.name} is missing from book/_toc.yml"


def test_jupyter_book_is_pinned_below_2():
    pins = (ROOT / "requirements" / "constraints.txt").read_text()
    m = re.search(r"^jupyter-book==(\d+)\.", pins, re.M)
    assert m and int(m.group(1)) < 2
    assert "jupyter-book>=1,<2" in (ROOT / "pyproject.toml").read_text()


def test_readme_gives_the_two_commands():
    readme = (ROOT / "README.md").read_text()
    assert "make course" in readme and "make test" in readme
    assert "make test" in (ROOT / ".ci" / "run").read_text()


@pytest.mark.parametrize(
    "path",
    sorted(
        p.relative_to(ROOT).as_posix() for d in ("shapelab", "course", "benchmarks") for p in (ROOT / d).rglob("*.py")
    ),
)
def test_source_compiles_without_warnings(path):
    """An invalid escape such as ``\\m`` in a docstring is a warning today (it reached CI's
    output once) and an error in a later Python: compile every file with warnings as errors."""
    import warnings

    source = (ROOT / path).read_text(encoding="utf-8")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        compile(source, path, "exec")


def _sanitize(text: str) -> str:
    """Apply tests/nbval_sanitize.cfg the way nbval does: every section's regex, in order."""
    import configparser

    cfg = configparser.ConfigParser(interpolation=None)
    cfg.read(ROOT / "tests" / "nbval_sanitize.cfg", encoding="utf-8")
    for section in cfg.sections():
        text = re.sub(cfg[section]["regex"], cfg[section]["replace"], text)
    return text


@pytest.mark.parametrize(
    "a, b",
    [
        ("<shapelab.Balls object at 0x7f3a2c1d9e80>", "<shapelab.Balls object at 0x7f11aa0b3c10>"),
        ("<Figure size 800x450 with 1 Axes>", "<Figure size 640x480 with 2 Axes>"),
        ('<path id="m3f2a9c81d0" d="M 0 0"/>', '<path id="m77bb01e2fa" d="M 0 0"/>'),
        ('<use xlink:href="#m3f2a9c81d0" x="1"/>', '<use xlink:href="#m77bb01e2fa" x="1"/>'),
        ('<g clip-path="url(#p3a9f1c2d4e)">', '<g clip-path="url(#p0b1c2d3e4f)">'),
        ("built 2026-11-23T09:41:07Z", "built 2027-01-02T17:00:00Z"),
        ("brute force 0.45 s, k-d tree 12 ms", "brute force 0.61 s, k-d tree 9 ms"),
        ("early break is 3.1× faster", "early break is 2.7× faster"),
        ("peak 575 MiB", "peak 612 MiB"),
    ],
)
def test_sanitize_equates_what_changes_between_runs(a, b):
    assert a != b and _sanitize(a) == _sanitize(b)


@pytest.mark.parametrize(
    "a, b",
    [
        ("accelerated   35 iterations, final error 0.68°", "accelerated   22 iterations, final error 0.46°"),
        ("area 12.5664, perimeter 12.5664", "area 12.5665, perimeter 12.5664"),
        ("Betti (β₀, β₁) = (1, 4)", "Betti (β₀, β₁) = (1, 3)"),
        ("τ = 0.891", "τ = 0.892"),
    ],
)
def test_sanitize_keeps_the_numbers_a_lesson_teaches(a, b):
    assert _sanitize(a) != _sanitize(b)


def _pin_versions():
    import course.pins

    return course.pins


def test_pins_merge_the_freeze_with_the_overrides(tmp_path):
    pv = _pin_versions()
    freeze = tmp_path / "freeze.txt"
    freeze.write_text("numpy==2.4.6\nSciPy==1.17.1\nsoupsieve==4.1.2\npip==26.3\nshapelab==0.1.0\n")
    overrides = tmp_path / "overrides.txt"
    overrides.write_text(
        "# why each\n"
        'pywinpty==3.1.2 ; os_name == "nt"  # Windows only\n'
        'soupsieve==2.10 ; python_full_version < "3.11.5"  # 4.1.2 needs 3.11.5\n'
        'soupsieve==4.1.2 ; python_full_version >= "3.11.5"  # the freeze\'s\n'
    )
    f, o = pv._read(str(freeze)), pv.read_overrides(overrides)
    assert pv.merge(f, o) == [
        "numpy==2.4.6",
        'pywinpty==3.1.2 ; os_name == "nt"  # Windows only',
        "SciPy==1.17.1",
        'soupsieve==2.10 ; python_full_version < "3.11.5"  # 4.1.2 needs 3.11.5',
        'soupsieve==4.1.2 ; python_full_version >= "3.11.5"  # the freeze\'s',
    ]
    assert pv.coverage_errors(f, o) == []
    # an override that leaves a Python without a pin of a package the freeze has, or pins it twice
    gap = tmp_path / "gap.txt"
    gap.write_text('numpy==2.3.5 ; python_version >= "3.12"  # why\nnumpy==2.4.6 ; python_version >= "3.13"  # why\n')
    errors = pv.coverage_errors(f, pv.read_overrides(gap))
    assert any("no line holds on linux-x86_64, CPython 3.11" in e for e in errors)
    assert any("2 lines hold on windows-amd64, CPython 3.14" in e for e in errors)
    bad = tmp_path / "bad.txt"
    bad.write_text("numpy==2.4.6\nnumpy>=2\n")
    with pytest.raises(SystemExit, match=r"bad\.txt:2: expected 'name==version'"):
        pv._read(str(bad))
    silent = tmp_path / "silent.txt"
    silent.write_text("numpy==2.4.6\n")
    with pytest.raises(SystemExit, match="say why"):
        pv.read_overrides(silent)


def test_one_version_source():
    """The version lives in shapelab/__init__.py only; pyproject.toml reads it."""
    import importlib.metadata
    from pathlib import Path

    import shapelab

    text = (Path(__file__).resolve().parents[2] / "pyproject.toml").read_text()
    assert 'dynamic = ["version"]' in text and "\nversion =" not in text.split("[tool.setuptools.dynamic]")[0]
    assert importlib.metadata.version("shapelab") == shapelab.__version__
