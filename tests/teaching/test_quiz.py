"""The end-of-part quizzes (shapelab.check.quiz): well-formed, and checked without giving
the answers away."""

from __future__ import annotations

import itertools
import re

import pytest

from shapelab.check import quizzes as Q


def _key(part):
    """The accepted letters, found by trying every option (the digests are the only key)."""
    return {n: [l for l in Q.LETTERS if q.accepts(part, n, l)] for n, q in enumerate(Q.QUIZZES[part], 1)}


@pytest.mark.parametrize("part", sorted(Q.QUIZZES))
def test_every_question_has_four_distinct_options_and_exactly_one_answer(part):
    for n, q in enumerate(Q.QUIZZES[part], 1):
        assert len(q.options) == 4 and len(set(q.options)) == 4, (part, n)
        assert len(_key(part)[n]) == 1, (part, n)


def test_the_answers_are_not_all_the_same_letter():
    letters = [v[0] for part in Q.QUIZZES for v in _key(part).values()]
    assert len(set(letters)) >= 3


@pytest.mark.parametrize("part", sorted(Q.QUIZZES))
def test_right_answers_pass_and_any_wrong_one_fails_without_revealing_the_key(part, capsys):
    key = {n: v[0] for n, v in _key(part).items()}
    assert Q.quiz(part, key, quiet=True).passed
    assert Q.quiz(part, {str(n): a.upper() for n, a in key.items()}, quiet=True).passed  # forgiving form
    for n in key:
        for wrong in set(Q.LETTERS) - {key[n]}:
            answers = {**key, n: wrong}
            r = Q.quiz(part, answers)
            out = capsys.readouterr().out
            assert not r.passed and f"question {n}" in r.message
            assert out.count("\n") == 1  # printed once
            assert not re.search(r"\b[abcd]\b", r.message.split(":", 1)[1]), r.message


@pytest.mark.parametrize("answers", [None, {}, "b", 0, [1, 2]])
def test_no_answer_fails(answers):
    r = Q.quiz("I", answers, quiet=True)
    assert not r.passed and "not answered" in r.message


def test_partial_odd_and_extra_answers_are_named():
    r = Q.quiz("II", {1: "a", 2: 3, 9: "b"}, quiet=True)
    assert not r.passed
    assert "no answer to 3, 4, 5, 6" in r.message and "a letter a–d for 2" in r.message
    assert "no question 9" in r.message


def test_guessing_one_letter_everywhere_never_passes():
    for part, letter in itertools.product(Q.QUIZZES, Q.LETTERS):
        n = len(Q.QUIZZES[part])
        assert not Q.quiz(part, {i: letter for i in range(1, n + 1)}, quiet=True).passed


@pytest.mark.parametrize("part, exc", [("IV", ValueError), (1, TypeError), (None, TypeError)])
def test_a_bad_part_is_refused(part, exc):
    with pytest.raises(exc, match="part"):
        Q.quiz(part, {1: "a"})


def test_the_markdown_lists_every_option():
    for part, questions in Q.QUIZZES.items():
        text = Q.quiz_markdown(part)
        for q in questions:
            assert q.text in text and all(o in text for o in q.options)
