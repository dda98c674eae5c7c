"""Self-checks of lessons 15–17 (shapelab/check/rotation.py).

For every check: an independent correct student function passes, a plausible wrong
one fails with the first failing input in the message, and a crashing one is
reported, not raised.
"""

from __future__ import annotations

import numpy as np
import pytest

from shapelab import check

# ----------------------------------------------------------------- student solutions


def product_right(q, r):
    a0, a = q[0], np.asarray(q[1:])
    b0, b = r[0], np.asarray(r[1:])
    return np.concatenate([[a0 * b0 - a @ b], a0 * b + b0 * a + np.cross(a, b)])


def product_as_in_the_notes(q, r):  # the notes' k component, sign flipped
    out = product_right(q, r)
    out[3] = q[0] * r[3] - q[1] * r[2] + q[2] * r[1] + q[3] * r[0]
    return out


def product_commuted(q, r):
    return product_right(r, q)


def matrix_right(q):
    w, v = q[0], np.asarray(q[1:])
    skew = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return (w * w - v @ v) * np.eye(3) + 2 * np.outer(v, v) + 2 * w * skew  # Rodrigues' form


def matrix_transposed(q):
    return matrix_right(q).T


def rotation_right(R, G):
    """Kabsch by SVD, converted to a quaternion by the trace formula."""
    u, _, vt = np.linalg.svd(R.T @ G)
    d = np.sign(np.linalg.det(vt.T @ u.T))
    X = vt.T @ np.diag([1, 1, d]) @ u.T
    w = np.sqrt(max(0.0, 1 + np.trace(X))) / 2
    if w > 1e-3:
        return np.array([w, X[2, 1] - X[1, 2], X[0, 2] - X[2, 0], X[1, 0] - X[0, 1]]) / np.r_[1, 4 * w, 4 * w, 4 * w]
    # near a half turn: the axis is the eigenvector of X for eigenvalue 1
    vals, vecs = np.linalg.eig(X)
    axis = np.real(vecs[:, np.argmin(np.abs(vals - 1))])
    return np.r_[0.0, axis]  # angle pi (good enough for the cases used)


def rotation_negated(R, G):
    return -rotation_right(R, G)  # q and -q: the same rotation, must pass


def rotation_swapped(R, G):
    return rotation_right(G, R)  # rotates G onto R: the inverse


def _horn(R, G):  # the notes' A = sum of R_j^T G_j, written out from M = sum r g^T
    S = np.einsum("ja,jb->ab", R, G)
    d = [S[1, 2] - S[2, 1], S[2, 0] - S[0, 2], S[0, 1] - S[1, 0]]
    return np.array(
        [
            [np.trace(S), *d],
            [d[0], S[0, 0] - S[1, 1] - S[2, 2], S[0, 1] + S[1, 0], S[0, 2] + S[2, 0]],
            [d[1], S[0, 1] + S[1, 0], -S[0, 0] + S[1, 1] - S[2, 2], S[1, 2] + S[2, 1]],
            [d[2], S[0, 2] + S[2, 0], S[1, 2] + S[2, 1], -S[0, 0] - S[1, 1] + S[2, 2]],
        ]
    )


def rotation_largest_magnitude(R, G):  # the eigenvalue largest in |lambda| (power iteration's)
    lam, X = np.linalg.eigh(_horn(R, G))
    return X[:, np.argmax(np.abs(lam))]


def centroid_right(R, G):
    return np.mean(G, axis=0) - np.mean(R, axis=0)


def centroid_reversed(R, G):
    return np.mean(R, axis=0) - np.mean(G, axis=0)


def crashes(*args):
    raise IndexError("index 4 is out of bounds")


# ----------------------------------------------------------------- the checks


@pytest.mark.parametrize(
    "checker, right, wrongs",
    [
        (check.quaternion_product, product_right, [product_as_in_the_notes, product_commuted]),
        (check.rotation_matrix, matrix_right, [matrix_transposed]),
        (check.optimal_rotation, rotation_right, [rotation_swapped, rotation_largest_magnitude]),
        (check.centroid_alignment, centroid_right, [centroid_reversed]),
    ],
)
def test_right_passes_wrong_fails_crash_is_reported(checker, right, wrongs, capsys):
    result = checker(right)
    out = capsys.readouterr().out
    assert result.passed and "✓" in out and "correct" in out, out
    for wrong in wrongs:
        result = checker(wrong)
        out = capsys.readouterr().out
        assert not result.passed
        assert "✗" in out and "expected:" in out and "received:" in out and "First failing input" in out
    result = checker(crashes)
    out = capsys.readouterr().out
    assert not result.passed and "raised IndexError" in out


def test_horn_eigenvector_passes_and_largest_magnitude_fails(capsys):
    def horn_top(R, G):
        return np.linalg.eigh(_horn(R, G))[1][:, -1]

    assert check.optimal_rotation(horn_top)  # the oracle's matrix is Horn's
    assert not check.optimal_rotation(rotation_largest_magnitude)
    # right wherever lambda_1 is largest in magnitude, wrong on a mirror image (lambda_4 < -lambda_1),
    # whichever way a tie |lambda_1| = |lambda_4| (a planar case) is broken
    M = np.random.default_rng(5).normal(size=(12, 3)) * [2.0, 1.2, 0.6]
    M -= M.mean(axis=0)
    lam = np.linalg.eigvalsh(_horn(M, M * [1.0, 1.0, -1.0]))
    assert -lam[0] > lam[-1] > 0


def test_sign_of_the_quaternion_does_not_matter(capsys):
    assert check.optimal_rotation(rotation_negated)
    assert check.optimal_rotation(lambda R, G: rotation_right(R, G).tolist())  # a list is fine


def test_notes_product_fails_on_the_first_table_entry(capsys):
    result = check.quaternion_product(product_as_in_the_notes)
    assert result.n_cases == 1  # ij = k already fails


def test_wrong_shape_or_nan_fails_without_raising(capsys):
    assert not check.optimal_rotation(lambda R, G: np.zeros(3))
    assert not check.optimal_rotation(lambda R, G: np.full(4, np.nan))
    assert not check.rotation_matrix(lambda q: np.eye(4))
    assert not check.centroid_alignment(lambda R, G: "t")


def test_placeholder_and_non_callable(capsys):
    def placeholder(q, r):
        raise NotImplementedError

    result = check.quaternion_product(placeholder)
    assert not result.passed and "not implemented yet" in capsys.readouterr().out
    result = check.rotation_matrix(np.eye(3))
    assert not result.passed and "expected a function" in capsys.readouterr().out


def test_quiet_prints_nothing(capsys):
    assert check.centroid_alignment(centroid_right, quiet=True)
    assert capsys.readouterr().out == ""
