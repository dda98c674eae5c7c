"""Quizzes at the end of each part of the course, self-checked without giving answers away.

The course has three parts: I, the union of balls (lessons 00–06); II, voids, pockets,
tunnels and persistence (07–12); III, shape matching (13–17).  The last lesson of each
part ends with its quiz: :func:`show_quiz` renders the questions, the student writes
``answers = {1: "b", 2: ...}`` and :func:`quiz` says which are right.

The answer key is stored as salted SHA-256 digests, so neither the library's source nor
a check's output shows a correct option; a wrong answer is reported by its question
number only.  (Four options cannot keep a secret from a determined reader: the point is
that nothing prints the answer by accident.)
"""

from __future__ import annotations

import hashlib
from collections.abc import Mapping
from dataclasses import dataclass

from ._runner import CheckResult

__all__ = ["Question", "QUIZZES", "quiz", "show_quiz", "quiz_markdown"]

LETTERS = "abcd"


def _digest(part: str, number: int, letter: str) -> str:
    return hashlib.sha256(f"shapelab-quiz:{part}:{number}:{letter}".encode()).hexdigest()[:20]


@dataclass(frozen=True)
class Question:
    """One multiple-choice question: its text, four options, the digest of the answer.

    See Also
    --------
    quiz
        Asks questions.
    """

    text: str
    options: tuple
    key: str

    def accepts(self, part: str, number: int, letter: str) -> bool:
        return _digest(part, number, letter) == self.key


def _q(text, options, key):
    return Question(text, tuple(options), key)


#: The quizzes, by part.  Each key is ``_digest(part, number, correct letter)``.
QUIZZES: dict[str, tuple[Question, ...]] = {
    "I": (
        _q(
            "The power distance $\\pi_i(x) = \\|x - z_i\\|^2 - r_i^2$ of a point $x$ from the ball $B_i$ is negative when",
            [
                "$x$ lies outside $B_i$",
                "$x$ lies inside $B_i$",
                "$x$ lies on the sphere bounding $B_i$",
                "never: it is a squared distance",
            ],
            "208dff8284633d7d68ec",
        ),
        _q(
            "The points with equal power distance from two balls (with distinct centres) form",
            [
                "a hyperbola",
                "a sphere",
                "the perpendicular bisector of the centres, whatever the radii",
                "a hyperplane orthogonal to the line through the centres",
            ],
            "647c9619c71421938793",
        ),
        _q(
            "The power cell of a ball is empty exactly when",
            [
                "the ball is hidden: other balls have smaller power distance everywhere",
                "never",
                "two balls have the same radius",
                "the ball is the largest",
            ],
            "8b70a4860dc3dcf76083",
        ),
        _q(
            "In the growth model, at time $\\tau$ a ball of radius $r$ has radius",
            ["$r + \\tau$", "$r\\,\\tau$", "$\\sqrt{r^2 + \\tau}$", "$r^2 + \\tau$"],
            "877f3461d07936855fba",
        ),
        _q(
            "The dual complex $K$ of a union of balls has, in general,",
            [
                "the same shape as the union",
                "the same homotopy type as the union: components, holes and voids",
                "more holes than the union",
                "the same volume as the union",
            ],
            "16f79cfea7d0ba4d8d55",
        ),
        _q(
            "The short inclusion–exclusion formula for the area of a union of disks sums over",
            [
                "all subsets of the disks",
                "the triangles of the Delaunay triangulation of the centres",
                "the pairs of disks only",
                "the simplices of the dual complex $K$",
            ],
            "f6c7b0796410a12044a5",
        ),
    ),
    "II": (
        _q(
            "A void of a union of balls is",
            [
                "a bounded component of the complement",
                "any concave region of the boundary",
                "a class of $H_1$",
                "a hidden ball",
            ],
            "9eda76c280348c9c06af",
        ),
        _q(
            "In the growth model, a pocket at time $\\tau$ is",
            [
                "a void at $\\tau$",
                "a tunnel",
                "a region still connected to the outside at $\\tau$ that becomes a void later",
                "any region within one probe radius of the surface",
            ],
            "cb0ecc03b2fd34610a95",
        ),
        _q(
            "A tunnel through a molecule corresponds to",
            ["a void", "a class of $H_2$", "a component ($H_0$)", "a class of $H_1$"],
            "c44b6cc8f1982d8a1835",
        ),
        _q(
            "The persistence of a feature in the growth model measures",
            [
                "its volume",
                "how long it lives as the balls grow (death minus birth), not its size",
                "its surface area",
                "the number of balls that line it",
            ],
            "9f9f5adeab8ef27e3b61",
        ),
        _q(
            "By the elder rule, when two components merge",
            ["the older one dies", "both die", "the younger one (born later) dies", "neither dies"],
            "e0fb94949bcb83212e55",
        ),
        _q(
            "Growing every radius by a water probe of 1.4 Å (the solvent-accessible model)",
            [
                "can seal a pocket with a narrow mouth into a void",
                "never changes which features are voids",
                "removes every void",
                "makes the union smaller",
            ],
            "b6f930fb1a58d645675b",
        ),
    ),
    "III": (
        _q(
            "The directed Hausdorff distance $h(R, G) = \\max_{r\\in R}\\min_{g\\in G} d(r, g)$ is",
            [
                "symmetric in $R$ and $G$",
                "always zero for sets of equal size",
                "not symmetric in general",
                "a metric on finite sets",
            ],
            "0cabd311256dd17c894d",
        ),
        _q(
            "For matching finite point sets under translation with the Hausdorff distance, the centroid",
            [
                "is not a reference point: points added close to one point move it far, while the Hausdorff distance hardly changes",
                "is a reference point",
                "gives the optimal translation",
                "is the bounding-box centre",
            ],
            "4f29f4d68cdc7a68f8a0",
        ),
        _q(
            "With closest-point pairing, the cost of ICP from one iteration to the next",
            [
                "can increase",
                "needs a one-to-one pairing to be defined",
                "always reaches the global minimum",
                "never increases",
            ],
            "d3b073c3a2e859bca758",
        ),
        _q(
            "A unit quaternion $q$ rotates a vector $r$ (as a pure quaternion) to",
            ["$q\\,r$", "$q\\,r\\,q^*$", "$q^*\\,r$", "$q^2\\,r$"],
            "e20aace77274d2a8f603",
        ),
        _q(
            "The unit quaternions $q$ and $-q$",
            ["are the same rotation", "are different rotations", "are inverse rotations", "are not both unit"],
            "0712d82f715262364455",
        ),
        _q(
            "Horn's optimal rotation is the unit eigenvector of his $4\\times4$ matrix $A$ for",
            ["its smallest eigenvalue", "the eigenvalue zero", "its largest eigenvalue", "any eigenvalue"],
            "9655478012ad21a067c8",
        ),
    ),
}

_TITLES = {
    "I": "Part I: the union of balls (lessons 00–06)",
    "II": "Part II: voids, pockets, tunnels and persistence (lessons 07–12)",
    "III": "Part III: shape matching (lessons 13–17)",
}


def _part(part) -> str:
    if not isinstance(part, str):
        raise TypeError(f"part must be a str such as 'I', got {type(part).__name__}")
    if part not in QUIZZES:
        raise ValueError(f"part must be one of {sorted(QUIZZES)}, got {part!r}")
    return part


def quiz_markdown(part: str) -> str:
    """The questions of ``part`` as Markdown (numbered, options a–d).

    See Also
    --------
    quiz
        Checks the answers.
    """
    part = _part(part)
    lines = [f"**Quiz, {_TITLES[part]}.** Answer with a dict `{{number: letter}}`.", ""]
    for n, q in enumerate(QUIZZES[part], 1):
        lines.append(f"{n}. {q.text}")
        lines += [
            f"   ({LETTERS[k]}) {opt}" + ("  " if k < len(q.options) - 1 else "") for k, opt in enumerate(q.options)
        ]
    return "\n".join(lines)


def show_quiz(part: str) -> None:
    """Display the questions of ``part`` (Markdown in a notebook, text elsewhere).

    See Also
    --------
    quiz
        Checks the answers.

    Examples
    --------
    >>> quiz_markdown("I").splitlines()[0]
    '**Quiz, Part I: the union of balls (lessons 00–06).** Answer with a dict `{number: letter}`.'
    >>> show_quiz("I")  # in a notebook: the questions as Markdown
    <IPython.core.display.Markdown object>
    """
    text = quiz_markdown(part)
    try:
        from IPython.display import Markdown, display

        display(Markdown(text))
    except ImportError:  # pragma: no cover - outside IPython
        print(text)


def quiz(part: str, answers: Mapping[int, str], *, quiet: bool = False) -> CheckResult:
    """Check the answers to the quiz of ``part`` without revealing the right options.

    Parameters
    ----------
    part : {"I", "II", "III"}
    answers : dict
        ``{question number: letter}``, e.g. ``{1: "b", 2: "a", ...}``; letters a–d.
    quiet : bool
        Do not print; only return the result.

    Returns
    -------
    CheckResult
        Passed when every question is answered correctly.  The message names the
        questions that are unanswered or wrong, never the right letters.

    See Also
    --------
    show_quiz
        Shows a quiz without checking.
    quiz_markdown
        A quiz as Markdown.

    Examples
    --------
    >>> result = quiz("I", {1: "a"})
    ✗ quiz, part I: 0 of 6 correct; look again at question 1; no answer to 2, 3, 4, 5, 6.
    >>> result.passed
    False
    """
    part = _part(part)
    name = f"quiz, part {part}"
    questions = QUIZZES[part]
    if not isinstance(answers, dict) or not answers:
        msg = f"… {name}: not answered yet. Write answers = {{1: 'a', 2: ...}} and run the cell again."
        return _finish(name, False, 0, msg, quiet)
    wrong, missing, bad = [], [], []
    for n in range(1, len(questions) + 1):
        a = answers.get(n, answers.get(str(n)))
        if a is None:
            missing.append(n)
        elif not isinstance(a, str) or a.strip().lower() not in LETTERS:
            bad.append(n)
        elif not questions[n - 1].accepts(part, n, a.strip().lower()):
            wrong.append(n)
    extra = sorted(k for k in answers if str(k) not in {str(n) for n in range(1, len(questions) + 1)})
    right = len(questions) - len(wrong) - len(missing) - len(bad)
    if right == len(questions) and not extra:
        return _finish(name, True, len(questions), f"✓ {name}: all {right} correct.", quiet)
    parts = [f"{right} of {len(questions)} correct"]
    if wrong:
        parts.append("look again at question" + ("s " if len(wrong) > 1 else " ") + ", ".join(map(str, wrong)))
    if missing:
        parts.append("no answer to " + ", ".join(map(str, missing)))
    if bad:
        parts.append("answer with a letter a–d for " + ", ".join(map(str, bad)))
    if extra:
        parts.append(f"there is no question {', '.join(map(str, extra))}")
    return _finish(name, False, len(questions), f"✗ {name}: " + "; ".join(parts) + ".", quiet)


def _finish(name: str, passed: bool, n: int, msg: str, quiet: bool) -> CheckResult:
    if not quiet:
        print(msg)
    return CheckResult(name, passed, n, msg)
