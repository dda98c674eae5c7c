"""Tests of the library, ``shapelab``: one module per library module, GUDHI comparisons in ``*_gudhi.py``."""
