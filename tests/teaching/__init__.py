"""Tests of the teaching layer: the self-checks, quizzes and the committed lessons."""
