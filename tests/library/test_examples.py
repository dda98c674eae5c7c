"""Every public function and class a lesson calls shows an example and says its types.

Issue 33: "Every public function a lesson calls has an Examples section that runs as a
doctest, and type annotations."  The names are the ones ``python -m course.lesson_calls``
lists (read from the lessons' code cells with ``ast``).  For each one this test asserts

* its docstring has a numpydoc ``Examples`` section with at least one ``>>>`` line (the
  doctests themselves run under ``pytest --doctest-modules shapelab``), and
* it is fully annotated: every parameter but ``self``/``cls`` and the return of a function;
  for a class, the parameters of its ``__init__`` (a dataclass's fields are annotated by
  construction).
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import re

import pytest

from course import lesson_calls

CALLS = lesson_calls.calls()
_EXAMPLES = re.compile(r"^Examples\n-{3,}\n(.*?)(?=^\S[^\n]*\n-{3,}\n|\Z)", re.S | re.M)


def _object(call: lesson_calls.Call) -> object:
    return getattr(importlib.import_module(call.module), call.name)


def _callable(obj: object) -> bool:
    return callable(obj) and not inspect.ismodule(obj)


def has_examples(obj: object) -> bool:
    """Whether ``obj``'s docstring has an ``Examples`` section with a ``>>>`` line."""
    doc = inspect.getdoc(obj) or ""
    section = _EXAMPLES.search(doc)
    return section is not None and ">>>" in section.group(1)


def missing_annotations(obj: object) -> list[str]:
    """The parameters (and ``return``) of ``obj`` that carry no annotation."""
    if inspect.isclass(obj):
        if dataclasses.is_dataclass(obj):
            return []
        init = obj.__dict__.get("__init__") or next(
            (
                k.__dict__["__init__"]
                for k in obj.__mro__[1:]
                if "__init__" in k.__dict__ and k.__module__.startswith("shapelab")
            ),
            None,
        )
        if init is None:
            return []
        sig, want_return = inspect.signature(init), False
    else:
        sig, want_return = inspect.signature(obj), True
    missing = [
        p.name
        for p in sig.parameters.values()
        if p.name not in ("self", "cls") and p.annotation is inspect.Parameter.empty
    ]
    if want_return and sig.return_annotation is inspect.Signature.empty:
        missing.append("return")
    return missing


def _ids(c: lesson_calls.Call) -> str:
    return c.qualname


CHECKED = [c for c in CALLS if _callable(_object(c))]


def test_the_lessons_call_many_names():
    assert len(CALLS) > 100
    assert any(c.qualname == "shapelab.filtration.alpha_filtration" for c in CALLS)
    assert any(c.qualname == "shapelab.check.answers.neck_closing" for c in CALLS)
    assert any(c.qualname == "shapelab.plot.balls.disks" for c in CALLS)  # plot.disks, through plot's _EXPORTS


@pytest.mark.parametrize("call", CHECKED, ids=_ids)
def test_has_an_example(call):
    assert has_examples(_object(call)), (
        f"{call.qualname} (lessons {', '.join(call.lessons)}) has no Examples section with >>>"
    )


@pytest.mark.parametrize("call", CHECKED, ids=_ids)
def test_is_annotated(call):
    missing = missing_annotations(_object(call))
    assert not missing, f"{call.qualname} lacks annotations for {missing}"


def test_the_checks_can_fail():
    def bare(x, y=1):
        """No example.

        Examples
        --------
        Prose only.
        """

    def good(x: int) -> int:
        """One.

        Examples
        --------
        >>> good(1)
        1

        See Also
        --------
        bare
        """
        return x

    assert not has_examples(bare) and missing_annotations(bare) == ["x", "y", "return"]
    assert has_examples(good) and missing_annotations(good) == []
