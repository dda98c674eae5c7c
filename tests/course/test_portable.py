"""course/portable.py: its comparison of lesson outputs, on tiny notebooks.

Only the diff logic and the variants' environments are tested here, cheaply and
deterministically; running lessons under other BLAS kernels is a local diagnostic,
never part of CI (CONTRIBUTING.md, *Portable outputs*).
"""

from pathlib import Path

import nbformat
import pytest
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook, new_output

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def cp():
    import course.portable

    return course.portable


@pytest.fixture(scope="module")
def patterns(cp):
    return cp.get_sanitize_patterns(cp.SANITIZE.read_text())


def _stdout(*texts):
    return [new_output("stream", name="stdout", text=t) for t in texts]


def _nb(value="0.80°", took="0.45 s", png="AAAA", model="a" * 32):
    return new_notebook(
        cells=[
            new_markdown_cell("# 99 · Title"),
            new_code_cell("print(...)", outputs=_stdout(f"took {took}\n")),
            new_markdown_cell("## A section"),
            new_code_cell("print(...)", outputs=_stdout(f"final error {value}\n", "done\n")),
            new_code_cell(
                "fig",
                outputs=[
                    new_output(
                        "display_data",
                        data={
                            "text/plain": "<Figure size 800x450 with 1 Axes>",
                            "image/png": png,
                            "application/vnd.jupyter.widget-view+json": {"model_id": model},
                        },
                    )
                ],
            ),
        ]
    )


def test_identical_notebooks_do_not_differ(cp, patterns):
    assert cp.compare(_nb(), _nb(), patterns) == []


def test_what_nbval_ignores_or_sanitizes_does_not_differ(cp, patterns):
    fresh = _nb(took="1.7 s", png="BBBB", model="b" * 32)
    assert cp.compare(_nb(), fresh, patterns) == []


def test_split_streams_compare_as_one(cp, patterns):
    fresh = _nb()
    fresh.cells[3].outputs = _stdout("final ", "error 0.80°\ndone\n")
    assert cp.compare(_nb(), fresh, patterns) == []


def test_a_changed_number_is_reported_with_nbvals_cell_number(cp, patterns):
    found = cp.compare(_nb(value="0.80°"), _nb(value="0.68°"), patterns)
    assert len(found) == 1
    n, index, diff = found[0]
    assert (n, index) == (1, 3)  # nbval's "Cell 1" counts code cells; index 3 counts all cells
    assert "-final error 0.80°" in diff and "+final error 0.68°" in diff
    assert "done" not in diff


def test_a_new_output_and_an_error_are_reported(cp, patterns):
    fresh = _nb()
    fresh.cells[1].outputs.append(new_output("error", ename="ValueError", evalue="bad", traceback=[]))
    fresh.cells[4].outputs.append(new_output("stream", name="stderr", text="a warning\n"))
    found = cp.compare(_nb(), fresh, patterns)
    assert [n for n, _, _ in found] == [0, 2]
    assert "+ValueError: bad" in found[0][2]
    assert "+a warning" in found[1][2]


def test_different_notebooks_are_not_compared_cell_by_cell(cp, patterns):
    fresh = _nb()
    fresh.cells.append(new_code_cell("1"))
    [(n, _, diff)] = cp.compare(_nb(), fresh, patterns)
    assert n == -1 and "3 and 4 code cells" in diff


def test_notebooks_survive_a_round_trip_through_a_file(cp, patterns, tmp_path):
    nbformat.write(_nb(), tmp_path / "a.ipynb")
    assert cp.compare(nbformat.read(tmp_path / "a.ipynb", as_version=4), _nb(), patterns) == []


def test_variant_environments(cp):
    base = {"OPENBLAS_CORETYPE": "Zen", "OPENBLAS_L2_SIZE": "1048576", "PATH": "/bin"}
    assert cp.variant_env("current", base) == base
    assert cp.variant_env("blas-unset", base) == {"PATH": "/bin"}
    assert cp.variant_env("blas-sandybridge", base) == {"OPENBLAS_CORETYPE": "Sandybridge", "PATH": "/bin"}
    simd = cp.variant_env("npy-simd", base)["NPY_DISABLE_CPU_FEATURES"]
    assert isinstance(simd, str) and "X86_V2" not in simd.split()  # never the baseline
    assert base["OPENBLAS_CORETYPE"] == "Zen"  # the base is not modified
