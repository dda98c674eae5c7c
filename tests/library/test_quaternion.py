"""Quaternions (shapelab/quaternion.py; Notes §23.2).

Oracles independent of the code under test: the multiplication table of the basis
(i² = j² = k² = ijk = −1) extended bilinearly, the 2×2 complex-matrix representation
of the quaternions, SciPy's Rotation (which stores (x, y, z, w)!), and closed forms.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from scipy.spatial.transform import Rotation

from shapelab import Quaternion
from shapelab.quaternion import (
    from_scipy_order,
    left_matrices,
    qconj,
    qfrom_axis_angle,
    qfrom_matrix,
    qmatrix,
    qmul,
    qnorm,
    qnormalize,
    qrotate,
    right_matrices,
    rotation_angle,
    to_scipy_order,
)

ONE, I, J, K = (Quaternion(*row) for row in np.eye(4))

finite = st.floats(-10, 10, allow_nan=False, allow_infinity=False)
quat4 = hnp.arrays(np.float64, 4, elements=finite)
vec3 = hnp.arrays(np.float64, 3, elements=finite)
SET = settings(max_examples=60, deadline=None)


def unit(q):
    n = np.linalg.norm(q)
    return None if n < 1e-3 else q / n


unit4 = quat4.map(unit).filter(lambda q: q is not None)

# ----------------------------------------------------------------- oracles

# basis products e_a e_b = sign * e_c, from i^2 = j^2 = k^2 = ijk = -1 (Hamilton)
_TABLE = {
    (0, 0): (1, 0),
    (0, 1): (1, 1),
    (0, 2): (1, 2),
    (0, 3): (1, 3),
    (1, 0): (1, 1),
    (1, 1): (-1, 0),
    (1, 2): (1, 3),
    (1, 3): (-1, 2),
    (2, 0): (1, 2),
    (2, 1): (-1, 3),
    (2, 2): (-1, 0),
    (2, 3): (1, 1),
    (3, 0): (1, 3),
    (3, 1): (1, 2),
    (3, 2): (-1, 1),
    (3, 3): (-1, 0),
}


def table_product(q, r):
    out = np.zeros(4)
    for a in range(4):
        for b in range(4):
            s, c = _TABLE[(a, b)]
            out[c] += s * q[a] * r[b]
    return out


def su2(q):
    """The 2×2 complex matrix of q: a faithful representation of the quaternion algebra."""
    w, x, y, z = q
    return np.array([[w + 1j * x, y + 1j * z], [-y + 1j * z, w - 1j * x]])


def test_table_oracle_is_the_notes_relations():
    e = np.eye(4)
    minus_one = np.array([-1.0, 0, 0, 0])
    for a in (1, 2, 3):
        assert np.array_equal(table_product(e[a], e[a]), minus_one)
    assert np.array_equal(table_product(table_product(e[1], e[2]), e[3]), minus_one)


# ----------------------------------------------------------------- algebra


def test_basis_relations_of_the_notes():
    m1 = Quaternion(-1.0)
    assert I * I == m1 and J * J == m1 and K * K == m1 and I * J * K == m1
    assert I * J == K and J * I == -K
    assert J * K == I and K * J == -I
    assert K * I == J and I * K == -J


@SET
@given(quat4, quat4)
def test_product_matches_table_and_su2(q, r):
    ours = (Quaternion(*q) * Quaternion(*r)).as_array()
    np.testing.assert_allclose(ours, table_product(q, r), atol=1e-9)
    np.testing.assert_allclose(su2(ours), su2(q) @ su2(r), atol=1e-9)
    np.testing.assert_allclose(qmul(q, r), ours, atol=0)


@SET
@given(quat4, quat4, quat4)
def test_associative_not_commutative(a, b, c):
    A, B, C = Quaternion(*a), Quaternion(*b), Quaternion(*c)
    lhs, rhs = ((A * B) * C).as_array(), (A * (B * C)).as_array()
    np.testing.assert_allclose(lhs, rhs, atol=1e-9 * (1 + np.abs(lhs).max()))


@SET
@given(quat4, quat4)
def test_norm_is_multiplicative_and_conjugate_reverses(q, r):
    Q, R = Quaternion(*q), Quaternion(*r)
    assert np.isclose((Q * R).norm(), Q.norm() * R.norm(), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose((Q * R).conjugate().as_array(), (R.conjugate() * Q.conjugate()).as_array(), atol=1e-9)
    # q q* = |q|^2, and <q, r> is the dot product
    np.testing.assert_allclose((Q * Q.conjugate()).as_array(), [Q.norm() ** 2, 0, 0, 0], atol=1e-9)
    assert np.isclose(Q.inner(R), float(np.dot(q, r)), atol=1e-12)


def test_scalar_arithmetic_and_numpy_scalars():
    q = Quaternion(1, 2, 3, 4)
    assert 2 * q == q * 2 == Quaternion(2, 4, 6, 8)
    assert np.float64(2.0) * q == Quaternion(2, 4, 6, 8)  # not an array: numpy defers
    assert q / 2 == Quaternion(0.5, 1, 1.5, 2)
    assert q + q - q == q and -q == Quaternion(-1, -2, -3, -4)
    with pytest.raises(ZeroDivisionError):
        q / 0
    with pytest.raises(TypeError):
        q * "a"
    with pytest.raises(TypeError):
        q + 1


def test_immutable_hashable_float64():
    q = Quaternion(1, 2, 3, 4)
    with pytest.raises(dataclasses.FrozenInstanceError):
        q.w = 5.0
    assert {q: 1}[Quaternion(1.0, 2.0, 3.0, 4.0)] == 1
    assert type(q.w) is float and q.as_array().dtype == np.float64
    assert not hasattr(q, "__dict__")
    assert Quaternion.from_array([1, 2, 3, 4]) == q
    assert q.isclose(Quaternion(1 + 1e-13, 2, 3, 4)) and not q.isclose(-q)
    assert q.same_rotation(-q) and not q.same_rotation(Quaternion(1, 2, 3, 5))


# ----------------------------------------------------------------- matrix forms


@SET
@given(quat4, quat4)
def test_left_and_right_matrices(q, r):
    Q = Quaternion(*q)
    np.testing.assert_allclose(Q.left_matrix() @ r, table_product(q, r), atol=1e-9)
    np.testing.assert_allclose(Q.right_matrix() @ r, table_product(r, q), atol=1e-9)
    # Q and Q-bar commute (left and right multiplications commute by associativity)
    L, Rb = Q.left_matrix(), Q.right_matrix()
    np.testing.assert_allclose(L @ Rb, Rb @ L, atol=1e-9)
    # Q-bar is Q with its lower-right 3x3 block transposed (the notes' recipe)
    expect = L.copy()
    expect[1:, 1:] = L[1:, 1:].T
    np.testing.assert_array_equal(Rb, expect)
    # each is |q| times an orthogonal matrix
    np.testing.assert_allclose(L.T @ L, Q.norm() ** 2 * np.eye(4), atol=1e-8)


def test_batched_matrices_and_pure_vectors():
    rng = np.random.default_rng(0)
    qs = rng.normal(size=(5, 4))
    for k in range(5):
        np.testing.assert_array_equal(left_matrices(qs)[k], Quaternion(*qs[k]).left_matrix())
        np.testing.assert_array_equal(right_matrices(qs)[k], Quaternion(*qs[k]).right_matrix())
    v = rng.normal(size=3)
    np.testing.assert_array_equal(left_matrices(v), Quaternion.pure(v).left_matrix())


def test_notes_qbar_is_not_orthogonal_to_q():
    """The notes call Q̄ "the matrix orthogonal to Q": QᵀQ̄ is not zero."""
    q = Quaternion(1, 2, 3, 4)
    assert np.abs(q.left_matrix().T @ q.right_matrix()).max() > 1


@SET
@given(unit4, vec3)
def test_Iq_equals_QbarT_Q(q, r):
    """Notes §23.2: I_q(r) = q r q* = Q̄ᵀ Q r (this one is correct)."""
    Q = Quaternion(*q)
    r4 = np.concatenate([[0.0], r])
    lhs = (Q * Quaternion(*r4) * Q.conjugate()).as_array()
    np.testing.assert_allclose(Q.right_matrix().T @ Q.left_matrix() @ r4, lhs, atol=1e-9)
    np.testing.assert_allclose(lhs[1:], Q.rotate(r), atol=1e-9)
    assert abs(lhs[0]) < 1e-9
    np.testing.assert_allclose((Q.right_matrix().T @ Q.left_matrix())[1:, 1:], Q.to_matrix(), atol=1e-12)


# ----------------------------------------------------------------- rotations


@SET
@given(unit4, hnp.arrays(np.float64, (7, 3), elements=finite))
def test_rotate_matches_matrix_and_scipy(q, pts):
    Q = Quaternion(*q)
    scipy_rot = Rotation.from_quat([q[1], q[2], q[3], q[0]])  # scipy: (x, y, z, w)
    np.testing.assert_allclose(Q.rotate(pts), pts @ Q.to_matrix().T, atol=1e-9)
    np.testing.assert_allclose(Q.rotate(pts), scipy_rot.apply(pts), atol=1e-9)
    np.testing.assert_allclose(Q.to_matrix(), scipy_rot.as_matrix(), atol=1e-12)
    np.testing.assert_allclose(Q.rotate(pts[0]), scipy_rot.apply(pts[0]), atol=1e-9)
    np.testing.assert_allclose(Rotation.from_quat(to_scipy_order(q)).as_matrix(), Q.to_matrix(), atol=1e-12)
    np.testing.assert_array_equal(from_scipy_order(to_scipy_order(q)), q)


def test_rotate_normalises_a_non_unit_quaternion():
    q = Quaternion(1, 2, 3, 4)
    p = np.array([0.3, -1.0, 2.0])
    raw = (q * Quaternion.pure(p) * q.conjugate()).vector  # the scaled rotation |q|^2 R p
    np.testing.assert_allclose(raw, q.norm() ** 2 * q.rotate(p), atol=1e-12)
    assert np.isclose(np.linalg.norm(q.rotate(p)), np.linalg.norm(p))


def test_from_axis_angle_closed_forms():
    q = Quaternion.from_axis_angle([0, 0, 2], np.pi / 2)  # the axis is normalised
    np.testing.assert_allclose(q.as_array(), [np.sqrt(0.5), 0, 0, np.sqrt(0.5)], atol=1e-15)
    np.testing.assert_allclose(q.rotate([1.0, 0, 0]), [0, 1, 0], atol=1e-15)  # counter-clockwise
    np.testing.assert_allclose(Quaternion.from_axis_angle([1, 0, 0], np.pi).rotate([0, 1.0, 0]), [0, -1, 0], atol=1e-15)


@SET
@given(vec3.filter(lambda v: np.linalg.norm(v) > 1e-3), st.floats(-10, 10))
def test_axis_angle_round_trip_and_scipy(axis, angle):
    q = Quaternion.from_axis_angle(axis, angle)
    assert np.isclose(q.norm(), 1.0)
    ax, ang = q.to_axis_angle()
    assert 0.0 <= ang <= np.pi
    assert np.isclose(np.linalg.norm(ax), 1.0)
    assert Quaternion.from_axis_angle(ax, ang).same_rotation(q, 1e-9)
    rotvec = axis / np.linalg.norm(axis) * angle
    np.testing.assert_allclose(q.to_matrix(), Rotation.from_rotvec(rotvec).as_matrix(), atol=1e-9)
    expect = Rotation.from_rotvec(rotvec).magnitude()
    assert np.isclose(ang, expect, atol=1e-7)
    np.testing.assert_allclose(Quaternion.from_rotation_vector(rotvec).to_matrix(), q.to_matrix(), atol=1e-9)
    np.testing.assert_allclose(Rotation.from_rotvec(q.to_rotation_vector()).as_matrix(), q.to_matrix(), atol=1e-9)


def test_to_axis_angle_of_identity_and_negative_w():
    ax, ang = Quaternion(1.0).to_axis_angle()
    assert ang == 0.0 and np.array_equal(ax, [1, 0, 0])
    q = Quaternion.from_axis_angle([0, 1, 0], 3.0)
    ax, ang = (-q).to_axis_angle()  # -q: same rotation, still an angle in [0, pi]
    assert np.isclose(ang, 3.0) and np.allclose(ax, [0, 1, 0])
    ax, ang = Quaternion.from_axis_angle([0, 1, 0], -1.0).to_axis_angle()
    assert np.isclose(ang, 1.0) and np.allclose(ax, [0, -1, 0])


@SET
@given(unit4)
def test_matrix_round_trip_and_scipy(q):
    Q = Quaternion(*q)
    back = Quaternion.from_matrix(Q.to_matrix())
    assert back.same_rotation(Q, 1e-9) and back.w >= 0
    s = Rotation.from_matrix(Q.to_matrix()).as_quat()
    assert back.same_rotation(Quaternion(*from_scipy_order(s)), 1e-9)


@pytest.mark.parametrize("angle", [np.pi, np.pi - 1e-9, np.pi - 1e-5, 1e-9, 0.0])
def test_from_matrix_is_accurate_near_half_turn_and_identity(angle):
    """Shepperd's pivoting: no loss of accuracy where the trace is near -1 or 3."""
    rng = np.random.default_rng(1)
    for axis in rng.normal(size=(20, 3)):
        m = Rotation.from_rotvec(axis / np.linalg.norm(axis) * angle).as_matrix()
        q = Quaternion.from_matrix(m)
        np.testing.assert_allclose(q.to_matrix(), m, atol=2e-15 * 8)
        assert abs(q.norm() - 1) < 1e-15 * 4


def test_batched_functions_match_the_class():
    rng = np.random.default_rng(2)
    qs, rs, pts = rng.normal(size=(6, 4)), rng.normal(size=(6, 4)), rng.normal(size=(6, 3))
    prods = qmul(qs, rs)
    mats = qmatrix(qs)
    for k in range(6):
        Q = Quaternion(*qs[k])
        np.testing.assert_allclose(prods[k], (Q * Quaternion(*rs[k])).as_array(), atol=1e-12)
        np.testing.assert_allclose(mats[k], Q.to_matrix(), atol=1e-12)
        np.testing.assert_allclose(qrotate(qs[k], pts)[k], Q.rotate(pts[k]), atol=1e-12)
    np.testing.assert_allclose(qrotate(qs, pts), [Quaternion(*q).rotate(p) for q, p in zip(qs, pts)], atol=1e-12)
    np.testing.assert_allclose(qconj(qs)[:, 1:], -qs[:, 1:])
    np.testing.assert_allclose(qnorm(qs), np.linalg.norm(qs, axis=1))
    np.testing.assert_allclose(np.linalg.norm(qnormalize(qs), axis=1), 1.0)
    np.testing.assert_allclose(qmatrix(qfrom_matrix(mats)), mats, atol=1e-12)
    ax = rng.normal(size=(6, 3))
    ang = rng.normal(size=6)
    np.testing.assert_allclose(
        qmatrix(qfrom_axis_angle(ax, ang)),
        Rotation.from_rotvec(ax / np.linalg.norm(ax, axis=1, keepdims=True) * ang[:, None]).as_matrix(),
        atol=1e-12,
    )
    # qmul broadcasts one quaternion against many
    np.testing.assert_allclose(qmul(qs[0], rs), [qmul(qs[0], r) for r in rs])


@SET
@given(unit4, unit4)
def test_rotation_angle_matches_scipy(a, b):
    ra = Rotation.from_quat(to_scipy_order(a))
    rb = Rotation.from_quat(to_scipy_order(b))
    expect = (ra.inv() * rb).magnitude()
    assert np.isclose(rotation_angle(a, b), expect, atol=1e-7)
    assert np.isclose(Quaternion(*a).angle_to(Quaternion(*-b)), expect, atol=1e-7)


def test_rotation_angle_is_accurate_for_tiny_angles():
    q = Quaternion.from_axis_angle([1, 2, 3], 1e-10)
    assert np.isclose(Quaternion(1.0).angle_to(q), 1e-10, rtol=1e-6)


# ----------------------------------------------------------------- the notes' errors


def notes_product(q, r):
    """The component formula of q·r exactly as printed in the notes."""
    q0, q1, q2, q3 = q
    r0, r1, r2, r3 = r
    return np.array(
        [
            q0 * r0 - q1 * r1 - q2 * r2 - q3 * r3,
            q0 * r1 + q1 * r0 + q2 * r3 - q3 * r2,
            q0 * r2 - q1 * r3 + q2 * r0 + q3 * r1,
            q0 * r3 - q1 * r2 + q2 * r1 + q3 * r0,
        ]
    )


def test_notes_k_component_has_the_wrong_sign():
    # with the printed formula, ij = -k, contradicting ij = k stated one line above
    np.testing.assert_array_equal(notes_product(I.as_array(), J.as_array()), -K.as_array())
    # the other three components agree with the correct product
    rng = np.random.default_rng(3)
    q, r = rng.normal(size=(2, 4))
    np.testing.assert_allclose(notes_product(q, r)[:3], qmul(q, r)[:3], atol=1e-12)
    assert not np.isclose(notes_product(q, r)[3], qmul(q, r)[3])


def test_notes_matrix_times_q_is_q_squared_not_qr():
    rng = np.random.default_rng(4)
    q, r = rng.normal(size=(2, 4))
    Q = Quaternion(*q).left_matrix()
    np.testing.assert_allclose(Q @ q, qmul(q, q), atol=1e-12)  # what the notes compute
    np.testing.assert_allclose(Q @ r, qmul(q, r), atol=1e-12)  # what they mean


# ----------------------------------------------------------------- bad input


def test_zero_quaternion_is_not_a_rotation():
    z = Quaternion(0.0, 0.0, 0.0, 0.0)
    for call in (z.rotate,):
        with pytest.raises(ValueError, match="zero quaternion"):
            call([1.0, 0, 0])
    for call in (z.to_matrix, z.to_axis_angle, z.normalized, z.to_rotation_vector):
        with pytest.raises(ValueError, match="zero quaternion"):
            call()
    with pytest.raises(ValueError, match="zero quaternion"):
        qrotate([0, 0, 0, 0], [1.0, 0, 0])
    with pytest.raises(ValueError, match=r"q is the zero quaternion \(at index \(1,\)\)"):
        qmatrix([[1.0, 0, 0, 0], [0, 0, 0, 0]])
    assert z * Quaternion(1, 2, 3, 4) == z  # as an algebra element it is fine


@pytest.mark.parametrize(
    "call, exc, words",
    [
        (lambda: Quaternion(np.nan, 0, 0, 0), ValueError, "w must be finite"),
        (lambda: Quaternion(1, np.inf, 0, 0), ValueError, "x must be finite"),
        (lambda: Quaternion(1, 0, "a", 0), TypeError, "y must be a real number"),
        (lambda: Quaternion(1, 0, 0, 1j), TypeError, "z must be a real number"),
        (lambda: Quaternion.from_array([1, 2, 3]), ValueError, "q must have length 4"),
        (lambda: Quaternion.from_axis_angle([0, 0, 0], 1.0), ValueError, "axis must be a non-zero"),
        (lambda: Quaternion.from_axis_angle([0, 0, 1, 0], 1.0), ValueError, "axis must have 3"),
        (lambda: Quaternion.from_axis_angle([0, 0, 1], np.nan), ValueError, "angle must be finite"),
        (lambda: Quaternion.from_matrix(np.diag([1.0, 1.0, -1.0])), ValueError, "reflection"),
        (lambda: Quaternion.from_matrix(2 * np.eye(3)), ValueError, "orthogonal"),
        (lambda: Quaternion.from_matrix(np.eye(4)), ValueError, r"shape \(3, 3\)"),
        (lambda: Quaternion.from_matrix(np.full((3, 3), np.nan)), ValueError, "matrix must be finite"),
        (lambda: Quaternion(1.0).rotate(np.zeros((4, 2))), ValueError, r"points must have shape \(3,\) or \(n, 3\)"),
        (lambda: Quaternion(1.0).rotate([[np.nan, 0, 0]]), ValueError, "points must be finite"),
        (lambda: Quaternion(1.0).rotate("abc"), TypeError, "points"),
        (lambda: qmul([1, 2, 3], [1, 2, 3, 4]), ValueError, r"a must have shape \(4,\)"),
        (lambda: Quaternion(1.0).inner([1, 0, 0, 0]), TypeError, "other must be a Quaternion"),
        (lambda: Quaternion(1.0).isclose(Quaternion(1.0), atol=-1), ValueError, "atol must be non-negative"),
    ],
)
def test_bad_input_names_the_argument(call, exc, words):
    with pytest.raises(exc, match=words):
        call()


# ----------------------------------------------------------------- inverse, division, exp, log, powers
# Oracles: the 2×2 complex-matrix representation (the inverse, exp and log of a
# quaternion are those of its matrix: scipy.linalg.inv/expm/logm), SciPy's Slerp, and
# the values of numpy-quaternion's own tests (tests/library/test_quaternion.py, moble/quaternion).

Q_NPQ = Quaternion(1.1, 2.2, 3.3, 4.4)  # numpy-quaternion's Q, Qlog, Qexp (15 digits given)
QLOG_NPQ = Quaternion(1.7959088706354, 0.515190292664085, 0.772785438996128, 1.03038058532817)
QEXP_NPQ = Quaternion(2.81211398529184, -0.392521193481878, -0.588781790222817, -0.785042386963756)
nonzero4 = quat4.filter(lambda q: np.linalg.norm(q) > 1e-3)


def from_su2(m):
    """The quaternion of a 2×2 complex matrix of the form su2(q.as_array())."""
    return Quaternion(m[0, 0].real, m[0, 0].imag, m[0, 1].real, m[0, 1].imag)


def close(a: Quaternion, b: Quaternion, rtol=1e-12) -> bool:
    return bool(np.abs(a.as_array() - b.as_array()).max() <= rtol * max(1.0, b.norm()))


def test_su2_oracle_reads_back():
    q = Quaternion(0.3, -1.2, 2.5, 0.7)
    assert from_su2(su2(q.as_array())) == q


@SET
@given(nonzero4, nonzero4)
def test_inverse_and_division(q, r):
    q, r = Quaternion(*q), Quaternion(*r)
    assert close(q * q.inverse(), ONE) and close(q.inverse() * q, ONE)
    assert close(q.inverse(), from_su2(np.linalg.inv(su2(q.as_array()))))
    assert close(q / r, q * r.inverse())  # right division
    assert close((q / r) * r, q, 1e-11)
    assert close(2.5 / q, 2.5 * q.inverse()) and close(q / 4.0, q * 0.25)
    assert close((q * r).inverse(), r.inverse() * q.inverse())


def test_division_table_of_numpy_quaternion():
    # from numpy-quaternion's test_quaternion_divide: exact on the basis
    assert I / I == ONE and J / J == ONE and K / K == ONE
    assert I / J == -K and I / K == J and J / I == K
    assert J / K == -I and K / I == -J and K / J == I
    for q in (ONE, I, J, K):
        assert ONE / q == q.conjugate() and q / ONE == q
    assert 0.0 / Q_NPQ == Quaternion(0.0) and Q_NPQ / 1 == Q_NPQ


def test_inverse_of_tiny_and_huge_quaternions_is_scaled():
    for s in (1e-160, 1e160):
        q = Quaternion(s, 2 * s, 0, 0)
        assert close(q * q.inverse(), ONE, 1e-15)


def test_zero_quaternion_has_no_inverse_log_or_negative_power():
    z = Quaternion(0.0)
    for call in (z.inverse, z.log, lambda: ONE / z, lambda: 2.0 / z, lambda: z**-1, lambda: z**-0.5):
        with pytest.raises(ValueError, match="zero quaternion"):
            call()
    assert z**0 == ONE and z**0.0 == ONE and z**2 == z and z**0.5 == z


def test_log_of_a_subnormal_vector_part_and_of_huge_norms():
    """log = ln|q| + atan2(|v|, q0) v/|v|: with |v| subnormal, atan2/|v| overflowed (a
    ValueError 'x must be finite, got inf' for (-1, 5e-324, 0, 0), whose log is pi i to
    rounding), and |q| overflowed for components near 1e308 (so log().exp() failed)."""
    for w in (-1.0, 1.0, 5e-324, -3.0):
        for v in (5e-324, 1e-310, -2e-308):
            q = Quaternion(w, 0.0, v, 0.0)
            ref = Quaternion(
                # ln sqrt(w² + v²) = ln max + ln(1 + (min/max)²)/2 (w² + v² underflows)
                np.log(max(abs(w), abs(v))) + np.log1p((min(abs(w), abs(v)) / max(abs(w), abs(v))) ** 2) / 2,
                0.0,
                np.arctan2(abs(v), w) * np.sign(v),
                0.0,
            )
            assert close(q.log(), ref, 1e-15), (w, v)
    for q in (Quaternion(1e308, 1e308, 1e308, 1e308), Quaternion(-1.5e308, 1e308, 0, -1e308)):
        L = q.log()
        a = np.array([q.w, q.x, q.y, q.z]) / 1e308
        assert L.w == pytest.approx(308 * np.log(10) + np.log(np.linalg.norm(a)), rel=1e-15)
        back = L.exp()
        np.testing.assert_allclose(back.as_array(), q.as_array(), rtol=1e-13)
    with pytest.raises(OverflowError, match="overflows"):
        Quaternion(710.0, 0.0, 0.0, 0.0).exp()


def test_overflowing_inverse_and_powers_raise_overflow_error():
    """They raised ValueError('w must be finite, got inf') (and RuntimeWarnings), unlike
    the real powers' OverflowError; the inverse of a subnormal quaternion is not a float."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for call in (
            lambda: Quaternion(5e-324).inverse(),
            lambda: 1.0 / Quaternion(0, 1e-310, 0, 0),
            lambda: Quaternion(2.0) ** 2000,
            lambda: Quaternion(1e200, 1e200, 0, 0) ** 2,
            lambda: Quaternion(2.0) ** 2000.0,
        ):
            with pytest.raises(OverflowError, match="overflows float64"):
                call()
        assert Quaternion(0.5) ** 2000 == Quaternion(0.0)


def test_log_exp_values_of_numpy_quaternion():
    tol = 1e-13  # the reference values are printed to 15 significant digits
    assert close(Q_NPQ.log(), QLOG_NPQ, tol)
    assert close(Q_NPQ.exp(), QEXP_NPQ, tol)
    assert close(Q_NPQ.log().exp(), Q_NPQ, tol)
    assert not close(Q_NPQ.exp().log(), Q_NPQ, tol)  # |v| = 5.9 > π: log is only a left inverse
    assert ONE.log() == Quaternion(0.0)
    for u in (I, J, K):
        assert u.log() == (np.pi / 2) * u
    assert (-ONE).log() == np.pi * I  # the negative real axis: numpy-quaternion's choice
    assert close(Quaternion(-3.0).log(), Quaternion(np.log(3.0), np.pi, 0, 0))


@SET
@given(nonzero4)
def test_exp_and_log_match_the_complex_matrix_functions(q):
    from scipy.linalg import expm, logm

    q = Quaternion(*q)
    assert close(q.exp(), from_su2(expm(su2(q.as_array()))), 1e-10)
    if np.linalg.norm(q.vector) > 1e-6 * q.norm():  # logm is ill-conditioned on the real axis
        assert close(q.log(), from_su2(logm(su2(q.as_array()))), 1e-8)
    assert close(q.log().exp(), q, 1e-12)


@SET
@given(unit4, vec3)
def test_unit_log_is_pure_half_rotation_vector_and_exp_inverts(q, v):
    q = Quaternion(*q)
    lg = q.log()
    assert abs(lg.w) < 1e-15
    if q.w >= 0:
        np.testing.assert_allclose(2 * lg.vector, q.to_rotation_vector(), atol=1e-12)
    v = v * (np.pi / (1e-9 + np.linalg.norm(v))) * 0.99  # |v| < π: exp then log round-trips
    p = Quaternion.pure(v)
    assert close(p.exp().log(), p, 1e-12)
    assert close(Quaternion.pure(v / 2).exp(), Quaternion.from_rotation_vector(v), 1e-14)


def test_exp_is_the_power_series():
    q = Quaternion(0.3, -0.8, 0.5, 1.1)
    term, total = ONE, ONE
    for k in range(1, 40):
        term = term * q / k
        total = total + term
    assert close(q.exp(), total, 1e-14)
    with pytest.raises(OverflowError, match="real part"):
        Quaternion(800.0).exp()


@SET
@given(nonzero4, st.integers(-7, 7))
def test_integer_powers_are_repeated_products(q, n):
    q = Quaternion(*q)
    ref = ONE
    for _ in range(abs(n)):
        ref = ref * (q if n > 0 else q.inverse())
    assert close(q**n, ref, 1e-12)
    assert close(q ** np.int64(n), ref, 1e-12)
    assert close(q ** float(n), ref, 1e-10)  # the real power agrees to rounding


def test_integer_powers_of_the_basis_are_exact():
    assert I**2 == -ONE and I**3 == -I and I**4 == ONE and I**-1 == -I
    q = Quaternion(1.0, 1.0, 0.0, 0.0)
    assert q**2 == Quaternion(0.0, 2.0, 0.0, 0.0) and q**4 == Quaternion(-4.0)


@SET
@given(nonzero4, st.floats(-3, 3), st.floats(-3, 3))
def test_real_powers_add_exponents(q, a, b):
    # (numpy-quaternion's test_quaternion_power: q**(s+t) = q**s q**t for any non-zero q)
    q = Quaternion(*q)
    assert close((q**a) * (q**b), q ** (a + b), 1e-9)
    assert close((q**a) / (q**b), q ** (a - b), 1e-9)
    assert close((q**0.5) * (q**0.5), q, 1e-12)
    assert close(q**-1.0, q.inverse(), 1e-12) and close(q**1.0, q, 1e-12)


@SET
@given(unit4, st.floats(0, 1))
def test_unit_power_scales_the_angle(q, t):
    q = Quaternion(*q)
    if q.w < 0:
        q = -q
    axis, angle = q.to_axis_angle()
    assert (q**t).same_rotation(Quaternion.from_axis_angle(axis, t * angle), 1e-12)
    assert abs((q**t).norm() - 1.0) < 1e-14


@SET
@given(unit4, unit4, st.floats(0, 1))
def test_slerp_is_a_power_and_matches_scipy(a, b, t):
    from scipy.spatial.transform import Slerp

    q0, q1 = Quaternion(*a), Quaternion(*b)
    if q0.inner(q1) < 0:
        q1 = -q1  # the shorter arc, as SciPy's Slerp takes it
    mine = q0 * (q0.inverse() * q1) ** t
    key = Rotation.from_quat(to_scipy_order(np.stack([q0.as_array(), q1.as_array()])))
    ref = Slerp([0.0, 1.0], key)([t])
    assert mine.same_rotation(Quaternion(*from_scipy_order(ref.as_quat()[0])), 1e-9)
    # the closed form sin((1-t)Ω)/sin Ω q0 + sin(tΩ)/sin Ω q1
    om = np.arccos(np.clip(q0.inner(q1), -1, 1))
    if om > 1e-3:
        ref2 = q0 * (np.sin((1 - t) * om) / np.sin(om)) + q1 * (np.sin(t * om) / np.sin(om))
        assert close(mine, ref2, 1e-9)


def test_power_and_division_refuse_non_numbers():
    with pytest.raises(TypeError):
        ONE ** "2"
    with pytest.raises(TypeError):
        ONE**True
    with pytest.raises(TypeError, match="exponent"):
        ONE.power(1j)
    with pytest.raises(TypeError):
        ONE / "a"
    with pytest.raises(ValueError, match="exponent must be finite"):
        ONE ** float("nan")
