"""Wrong answers of the right type and shape, made from a solution's own value.

``tests/teaching/test_selfchecks.py`` runs each exercise's solution in a Jupyter kernel, then
imports this module there and replaces each answer with every one of
:func:`mutants`'s values in turn before running the cell's self-check again: each must
fail.  Because the wrong answers are derived from the solution's value (a number off by
10 %, one entry of an array changed, a label replaced by another residue, a function that
is wrong on one input), they follow the lessons when the lessons change.

Where a generic change would still be a right answer (any threshold between two
persistences is right; a viewpoint moved by 10 % sees the same critical points) or the
answer is an object without a generic change, :data:`OVERRIDES` makes the wrong answers
from the lesson's own variables instead.
"""

from __future__ import annotations

import numbers

import numpy as np

__all__ = ["mutants", "perturb", "Unsupported", "OVERRIDES"]

LETTERS = "abcd"


class Unsupported(TypeError):
    """No generic wrong answer exists for a value of this type."""


def _rng(seed: int = 2323):
    return np.random.default_rng(seed)


def _off(v: float) -> float:
    """An amount that is wrong for every check's tolerance (the loosest is 5 % relative or
    0.05 absolute), and still 'a bit'."""
    return 0.1 * abs(float(v)) + 0.1


def perturb(v):
    """``v`` changed a little, keeping its type and shape (what a wrong function returns)."""
    if isinstance(v, (bool, np.bool_)):
        return type(v)(not v)
    if isinstance(v, numbers.Integral):
        return type(v)(v + 1)
    if isinstance(v, numbers.Real):
        return type(v)(v + _off(v))
    if isinstance(v, np.ndarray):
        w = v.copy()
        if w.size == 0:  # nothing to change: one row too many
            return np.ones((1,) + w.shape[1:], dtype=w.dtype)
        flat = w.reshape(-1)
        flat[0] = perturb(flat[0].item()) if w.dtype != object else perturb(flat[0])
        return w
    if isinstance(v, (list, tuple)) and len(v) > 0:
        return type(v)([perturb(v[0]), *v[1:]]) if not hasattr(v, "_fields") else type(v)(perturb(v[0]), *v[1:])
    name = type(v).__name__
    if name == "Quaternion":
        return type(v)(*(v.as_array() + np.array([0.0, 0.1, 0.0, 0.0])))
    if name == "RigidMotion":
        return type(v)(v.rotation, np.asarray(v.translation, dtype=float) + 0.1)
    raise Unsupported(f"no generic wrong value for a {name}")


def _fingerprint(x):
    if isinstance(x, np.ndarray):
        return ("array", x.shape, str(x.dtype), x.tobytes())
    if isinstance(x, (list, tuple)):
        return (type(x).__name__, *(_fingerprint(a) for a in x))
    if isinstance(x, (numbers.Number, str, bytes, type(None))):
        return x
    return ("object", id(x))


class _WrongFunction:
    """The solution's function, with its output perturbed on some inputs.

    ``where`` is ``"everywhere"``, ``"first"`` (only on the first input it is called with,
    the check's first case: an edge case) or ``"rest"`` (right on that first input, wrong
    on every other).  Which inputs are wrong depends on the inputs, not on the call count,
    so that calls outside the check agree with the calls inside it."""

    def __init__(self, fn, where: str):
        self.fn, self.where, self.first = fn, where, None
        self.unsupported = None
        self.__name__ = getattr(fn, "__name__", "f")

    def __call__(self, *args, **kwargs):
        out = self.fn(*args, **kwargs)
        key = _fingerprint(args)
        if self.first is None:
            self.first = key
        wrong = self.where == "everywhere" or ((key == self.first) == (self.where == "first"))
        if not wrong:
            return out
        try:
            return perturb(out)
        except Unsupported as exc:
            self.unsupported = str(exc)
            print(f"@@unsupported {exc}")
            return out


def _generic(v):
    rng = _rng()
    if callable(v) and not isinstance(v, type):
        return [
            ("wrong on every input", _WrongFunction(v, "everywhere")),
            ("wrong on the check's first input only", _WrongFunction(v, "first")),
            ("right on the first input only", _WrongFunction(v, "rest")),
        ]
    if isinstance(v, (bool, np.bool_)):
        return [("negated", type(v)(not v))]
    if isinstance(v, numbers.Integral):
        return [("one too many", type(v)(v + 1)), ("one too few", type(v)(v - 1))]
    if isinstance(v, numbers.Real):
        return [("10 % too large", type(v)(v + _off(v))), ("10 % too small", type(v)(v - _off(v)))]
    if isinstance(v, dict):
        if not v or not all(isinstance(a, str) and a in LETTERS for a in v.values()):
            raise Unsupported("a dict that is not a quiz's answers")
        keys = sorted(v)
        out = []
        for k in (keys[0], keys[-1]):
            w = dict(v)
            w[k] = LETTERS[(LETTERS.index(v[k]) + 1) % len(LETTERS)]
            out.append((f"answer {k} changed", w))
        return out
    if isinstance(v, np.ndarray) and v.dtype != object:
        if v.dtype == bool:
            rand = rng.random(v.shape) < 0.5
            if np.array_equal(rand, v):
                rand.reshape(-1)[0] ^= True
            return [("one entry flipped", perturb(v)), ("random booleans", rand)]
        if np.issubdtype(v.dtype, np.integer):
            return [("one entry off by one", perturb(v)), ("random integers", v + rng.integers(1, 3, v.shape))]
        scale = float(np.std(v)) if v.size > 1 and np.std(v) > 0 else 1.0
        rand = (rng.normal(size=v.shape) * scale + float(np.mean(v)) if v.size else v).astype(v.dtype)
        return [("one entry off by 10 %", perturb(v)), ("random values of the same shape", rand)]
    if isinstance(v, (list, tuple)) and v:
        if all(isinstance(a, str) for a in v):
            if len(v) < 2:
                raise Unsupported("a single label: no generic replacement")
            return [
                ("the last label replaced by a repeat of the first", type(v)([*v[:-1], v[0]])),
                ("the last label dropped", type(v)(v[:-1])),
            ]
        try:
            a = np.asarray(v)
        except (TypeError, ValueError) as exc:
            raise Unsupported(f"a {type(v).__name__} of mixed values") from exc
        if a.dtype == object:
            raise Unsupported(f"a {type(v).__name__} of objects")
        back = (
            (lambda w: type(v)(w.tolist())) if a.ndim == 1 else (lambda w: type(v)(type(v[0])(r) for r in w.tolist()))
        )
        return [(label, back(w)) for label, w in _generic(a)]
    try:
        return [("changed a little", perturb(v))]
    except Unsupported:
        raise Unsupported(f"no generic wrong answer for a {type(v).__name__}") from None


# ---- answers whose generic change may still be right, or that are objects -------------


def _eps_one_pocket(v, ns):
    pers = ns["pers"]
    return [
        ("a threshold that keeps two pockets", (pers[1] + pers[2]) / 2 if len(pers) > 2 else pers[1] / 2),
        ("a threshold that keeps none", pers[0] + 1.0),
    ]


def _residues(v, ns):
    mol, lining = ns["mol"], set(np.asarray(ns["pockets"][0].lining).tolist())
    others = sorted(
        {f"{n} {k}" for i, (n, k) in enumerate(zip(mol.residue_names, mol.residue_numbers)) if i not in lining}
        - set(v),
        key=lambda s: int(s.split()[1]),
    )
    universe = sorted({f"{n} {k}" for n, k in zip(mol.residue_names, mol.residue_numbers)})
    rng = _rng()
    return [
        ("random residues of the structure, as many", [universe[i] for i in rng.choice(len(universe), len(v), False)]),
        ("one label replaced by a residue off the pocket", [*v[:-1], others[len(others) // 2]]),
        ("one lining residue missing", list(v[1:])),
        ("one residue off the pocket too many", [*v, others[0]]),
        ("one label replaced by a repeat of another", [*v[:-1], v[0]]),
        ("the residue numbers off by one", [f"{s.split()[0]} {int(s.split()[1]) + 1}" for s in v]),
    ]


def _chis(v, ns):
    F, taus = ns["F"], ns["taus"]
    no_tets = [int(n[0] - n[1] + n[2]) for n in (F.complex_at(t).counts() for t in taus)]
    return [*_generic(v), ("tetrahedra left out", no_tets), ("the sphere's 2 at every τ", [2] * len(v))]


def _most_exposed(v, ns):
    area = ns["area_by_residue"]
    ranked = sorted(area, key=lambda k: (area[k], k), reverse=True)
    sl, mol = ns["sl"], ns["mol"]
    keys = [f"{n} {k}" for n, k in zip(mol.residue_names, mol.residue_numbers)]

    def top(values, how=sum):  # the residue whose atoms' values, combined by `how`, are largest
        by = {}
        for key, a in zip(keys, values):
            by.setdefault(key, []).append(float(a))
        return max(by, key=lambda k: (how(by[k]), k))

    vdw = sl.union_measure(mol.balls).ball_boundary
    sa = sl.union_measure(sl.Balls(mol.balls.centers, mol.balls.radii + 1.4)).ball_boundary
    plausible = [
        ("van der Waals radii, no probe", top(vdw)),
        ("the mean area per atom", top(sa, lambda a: sum(a) / len(a))),
        ("the residue of the most exposed atom", top(sa, max)),
    ]
    return [("the runner-up residue", ranked[1]), ("the least exposed residue", ranked[-1])] + [
        (label, w) for label, w in plausible if w != v
    ]


def _most_spread(v, ns):
    spread = ns["spread"]
    ranked = sorted(spread, key=lambda k: (spread[k], k), reverse=True)
    return [("the runner-up class", ranked[1]), ("the least spread class", ranked[-1])]


def _class_spreads(v, ns):
    """Lesson 19's per-class spreads, read the wrong way (each lands on the right class)."""
    labels = list(ns["labels"])

    def per_class(M, stat):
        out = {}
        for kind in dict.fromkeys(labels):
            idx = [i for i, s in enumerate(labels) if s == kind]
            out[kind] = float(stat(M[np.ix_(idx, idx)][np.triu_indices(len(idx), 1)]))
        return out

    H1 = ns["distance_matrix"]([d[1] for d in ns["dgms"]], p=2)
    first = next(iter(v))
    return [
        ("the mean distance within a class", per_class(ns["wasserstein"], np.mean)),
        ("H1's Wasserstein distance only", per_class(H1, np.max)),
        ("the bottleneck matrix", per_class(ns["bottleneck"], np.max)),
        ("one class's value 10 % off", {**v, first: v[first] + _off(v[first])}),
    ]


def _first_site_rank(v, ns):
    """Lesson 20: the flow's first rank at the ligand; wrong ranks a student may give: the
    growth model's (the table above the exercise), the first *row* of the flow's table,
    a 0-based index, one too many."""
    growth = next(r.id for r in ns["t4l_growth"].rows if ns["distance_to_ligand"](r, ns["t4l"], ns["xylene"]) <= 4.0)
    wrong = [("the growth model's rank", int(growth)), ("the first row, wherever it is", 1), ("a 0-based index", v - 1)]
    return [(label, w) for label, w in wrong if w != v] + [("one too many", v + 1)]


def _rips_gap(v, ns):
    import gudhi

    X = ns["small_torus"]
    st = gudhi.RipsComplex(points=X, max_edge_length=1.6).create_simplex_tree(max_dimension=2)
    st.compute_persistence(homology_coeff_field=2)
    rips = st.persistence_intervals_in_dimension(1)
    tau = np.asarray(ns["alpha_filtration"](ns["Balls"](X, 0.0)).persistence()[1], dtype=float)
    bd = ns["bottleneck_distance"]
    return [
        *_generic(v),
        ("Rips in the edge-length scale", float(bd(np.sqrt(np.maximum(tau, 0.0)), rips))),
        ("α left in the τ scale", float(bd(tau, rips / 2))),
        ("Rips values read as τ (square root taken)", float(bd(np.sqrt(np.maximum(tau, 0.0)), np.sqrt(rips)))),
        ("both in the τ scale", float(bd(tau, (rips / 2) ** 2))),
        (
            "the Delaunay–Čech complex, a nerve, instead of Rips",
            float(bd(np.sqrt(np.maximum(tau, 0.0)), _del_cech_h1(X))),
        ),
    ]


def _del_cech_h1(X):
    import gudhi

    st = gudhi.DelaunayCechComplex(X).create_simplex_tree(output_squared_values=False)
    st.compute_persistence(homology_coeff_field=2)
    return st.persistence_intervals_in_dimension(1)


def _viewpoints(v, ns):
    return [
        ("two viewpoints swapped against their counts", [v[1], v[0], v[2]]),
        ("three viewpoints far outside", [[5.0, 0.0, 0.0], [0.0, 5.0, 0.0], [0.0, 0.0, 5.0]]),
    ]


def _voids_after(v, ns):
    sl, back = ns["sl"], ns["back"]
    grown = sl.voids(sl.Balls(back.balls.centers, back.balls.radii * 0.97))
    return [("the void of a cage with radii 3 % small", grown), ("the void listed twice", [*v, *v])]


def _v_before(v, ns):
    sl, c60 = ns["sl"], ns["c60"]
    return [("the void of the cage with radii 3 % small", sl.voids(sl.Balls(c60.centers, c60.radii * 0.97))[0])]


def _icp_best(v, ns):
    return [("ICP from the identity only", ns["icp"](ns["src"], ns["tgt150"], max_iter=200))]


def _icp_step(v, ns):
    register, closest = ns["register"], ns["closest_points"]
    return [
        ("registration without closest points (rows paired in order)", lambda moved, target: register(moved, target)),
        (
            "the notes' step 2 literally: the motion of the target partners onto the source",
            lambda moved, target: register(target[closest(moved, target)[0]], moved),
        ),
    ]


def _horn_rotation(v, ns):
    horn = ns["horn_matrix"]

    def pick(which):
        def fn(R, G):
            lam, X = np.linalg.eigh(horn(R, G))
            return X[:, which(lam)]

        return fn

    return [
        *_generic(v),
        ("the smallest eigenvalue's eigenvector", pick(lambda lam: 0)),
        ("the eigenvalue largest in magnitude", pick(lambda lam: int(np.argmax(np.abs(lam))))),
        ("G rotated onto R (arguments swapped)", lambda R, G: v(G, R)),
        ("SciPy's order (x, y, z, w)", lambda R, G: np.roll(np.asarray(v(R, G)), -1)),
    ]


def _polyline_slopes(P, S):
    V = np.asarray(P, dtype=float)[:-1]
    R = V - S
    E = np.roll(V, -1, axis=0) - V
    return V, R, E, (R * E).sum(axis=1), (R * np.roll(E, 1, axis=0)).sum(axis=1)


def _maxima(v, ns):
    def non_strict(P, S):  # a zero slope taken for a turn
        V, R, E, leaving, arriving = _polyline_slopes(P, S)
        return np.sort(np.linalg.norm(R, axis=1)[(leaving <= 0) & (arriving >= 0)])

    def by_neighbours(P, S):  # compares each vertex with its two neighbouring vertices
        F = np.linalg.norm(np.asarray(P, dtype=float)[:-1] - S, axis=1)
        return np.sort(F[(F > np.roll(F, 1)) & (F > np.roll(F, -1))])

    return [
        *_generic(v),
        ("slopes compared with <= / >= (a regular vertex with one zero slope counted)", non_strict),
        ("each vertex compared with its neighbouring vertices", by_neighbours),
    ]


def _minima(v, ns):
    def closed_feet(P, S):  # a foot of the perpendicular at a vertex counted twice
        V, R, E, leaving, arriving = _polyline_slopes(P, S)
        at_vertices = np.linalg.norm(R, axis=1)[(leaving >= 0) & (arriving <= 0)]
        s = -leaving / (E * E).sum(axis=1)
        on = (s >= 0) & (s <= 1)
        return np.sort(np.concatenate([at_vertices, np.linalg.norm(V[on] + s[on, None] * E[on] - S, axis=1)]))

    def vertices_only(P, S):  # the feet inside edges left out
        V, R, E, leaving, arriving = _polyline_slopes(P, S)
        return np.sort(np.linalg.norm(R, axis=1)[(leaving >= 0) & (arriving <= 0)])

    return [
        *_generic(v),
        ("feet counted on the closed edge [0, 1] (a foot at a vertex counted twice)", closed_feet),
        ("the feet of perpendiculars inside edges left out", vertices_only),
    ]


# ---- students' mistakes that a generic change does not make ---------------------------


def _edge(v, ns):
    def strict(c1, r1, c2, r2):  # the circles cross: touching disks (closed cells meet) left out
        d = np.linalg.norm(np.subtract(c2, c1))
        return bool(abs(r1 - r2) < d < r1 + r2)

    return [*_generic(v), ("strict inequalities (touching disks have no edge)", strict)]


def _attached(v, ns):
    def orthocentre(z, r, i, j, weighted=True):
        a = z[j] - z[i]
        w = r**2 if weighted else 0 * r
        return z[i] + (a @ a - w[j] + w[i]) / (2 * (a @ a)) * a

    def diametral(centers, radii, edge):  # the unweighted Gabriel test: radii ignored
        z = np.asarray(centers, float)
        i, j = edge
        d = np.sum((z - (z[i] + z[j]) / 2) ** 2, axis=1)
        d[[i, j]] = np.inf
        return bool(np.any(d < np.sum((z[j] - z[i]) ** 2) / 4))

    def powers_at(midpoint=False, tie=False, nearest=False):
        def fn(centers, radii, edge):
            z, r = np.asarray(centers, float), np.asarray(radii, float)
            i, j = edge
            c = (z[i] + z[j]) / 2 if midpoint else orthocentre(z, r, i, j)
            pw = np.sum((z - c) ** 2, axis=1) - r**2
            rho, d2 = pw[i], np.sum((z - c) ** 2, axis=1)
            pw[[i, j]] = d2[[i, j]] = np.inf
            if nearest:
                return bool(pw[np.argmin(d2)] < rho)
            return bool(np.any(pw <= rho)) if tie else bool(np.any(pw < rho))

        return fn

    def centres_in_circle(centers, radii, edge):  # another centre inside the orthogonal circle
        z, r = np.asarray(centers, float), np.asarray(radii, float)
        i, j = edge
        c = orthocentre(z, r, i, j)
        d = np.sum((z - c) ** 2, axis=1)
        d[[i, j]] = np.inf
        return bool(np.any(d < np.sum((c - z[i]) ** 2) - r[i] ** 2))

    return [
        *_generic(v),
        ("the diametral circle (radii ignored)", diametral),
        ("centres, not powers", centres_in_circle),
        ("powers at the midpoint (the orthocentre of equal radii only)", powers_at(midpoint=True)),
        ("a tie counted as attached (<=)", powers_at(tie=True)),
        ("only the centre nearest c tested", powers_at(nearest=True)),
    ]


def _edge_time(v, ns):
    def foot_on_segment(c1, r1, c2, r2):  # the foot f clamped between the centres
        d = np.linalg.norm(np.subtract(c2, c1))
        return float(np.clip((d**2 + r1**2 - r2**2) / (2 * d), 0.0, d) ** 2 - r1**2)

    def equal_radii(c1, r1, c2, r2):  # (d/2)² − r1²: f at the midpoint
        return float((np.linalg.norm(np.subtract(c2, c1)) / 2) ** 2 - r1**2)

    return [
        *_generic(v),
        ("the foot of the radical axis clamped to the segment", foot_on_segment),
        ("the midpoint (equal radii) formula", equal_radii),
    ]


def _closes_at(v, ns):
    def equal_radii(pocket, balls):  # (d/2)² − r²: right only where the two radii are equal
        i, j = np.asarray(pocket.mouth).T
        d = np.linalg.norm(balls.centers[j] - balls.centers[i], axis=1)
        return float(np.max((d / 2) ** 2 - balls.radii[i] ** 2))

    def first_to_close(pocket, balls):  # the smallest of the mouth edges' times, not the largest
        i, j = np.asarray(pocket.mouth).T
        z, r = balls.centers, balls.radii
        d = np.linalg.norm(z[j] - z[i], axis=1)
        t = (d**2 + r[i] ** 2 - r[j] ** 2) / (2 * d)
        return float(np.min(t**2 - r[i] ** 2))

    return [
        *_generic(v),
        ("the equal-radii formula (d/2)² − r²", equal_radii),
        ("the mouth edge that closes first", first_to_close),
        ("the pocket's closes_at (a nested pocket's is its neck's)", lambda pocket, balls: pocket.closes_at),
    ]


def _flow_sinks(v, ns):
    def with_complex(F, tau):  # every centred triangle, also those already in K_tau
        z = F.balls.centers[np.asarray(F.simplices(2))]
        ok = np.ones(len(z), dtype=bool)
        for j in range(3):
            a, b, c = z[:, j], z[:, (j + 1) % 3], z[:, (j + 2) % 3]
            ok &= np.einsum("ij,ij->i", b - a, c - a) >= 0
        return np.flatnonzero(ok).tolist()

    def first_angle_only(F, tau):  # the obtuse test at the first vertex of each row only
        z = F.balls.centers[np.asarray(F.simplices(2))]
        a, b, c = z[:, 0], z[:, 1], z[:, 2]
        ok = (np.einsum("ij,ij->i", b - a, c - a) >= 0) & (np.asarray(F.values(2)) > tau)
        return np.flatnonzero(ok).tolist()

    def _centred(F, strict):  # no angle obtuse (strict: no right angle either)
        z = F.balls.centers[np.asarray(F.simplices(2))]
        ok = np.ones(len(z), dtype=bool)
        for j in range(3):
            a, b, c = z[:, j], z[:, (j + 1) % 3], z[:, (j + 2) % 3]
            dot = np.einsum("ij,ij->i", b - a, c - a)
            ok &= dot > 0 if strict else dot >= 0
        return ok

    def open_triangle(F, tau):  # circumcentre in the open triangle: right triangles flow
        return np.flatnonzero(_centred(F, True) & (np.asarray(F.values(2)) > tau)).tolist()

    def entering_is_empty(F, tau):  # values >= tau: a triangle entering at tau counted empty
        return np.flatnonzero(_centred(F, False) & (np.asarray(F.values(2)) >= tau)).tolist()

    return [
        *_generic(v),
        ("centred triangles of K_tau counted too", with_complex),
        ("one angle tested instead of three", first_angle_only),
        ("right triangles counted as flowing (open triangle)", open_triangle),
        ("a triangle entering at tau counted as empty", entering_is_empty),
    ]


def _r_closed(v, ns):
    return [*_generic(v), ("read off a grid of step 0.05, one step low", v - 0.05)]


def _closed_chain(v, ns):
    def degree_two(edges):  # a simple cycle's test: a figure eight has a vertex of degree 4
        e = np.asarray(edges).reshape(-1, 2)
        return bool(len(e) == 0 or np.all(np.unique(e, return_counts=True)[1] == 2))

    def as_many_edges_as_vertices(edges):  # a loop with a dangling edge has as many
        e = np.asarray(edges).reshape(-1, 2)
        return bool(len(e) == len(np.unique(e)))

    return [
        *_generic(v),
        ("every vertex of degree 2", degree_two),
        ("as many edges as vertices", as_many_edges_as_vertices),
    ]


def _betti_from_pairs(v, ns):
    def half_open_left(pairs, tau):  # (birth, death]: wrong exactly at births and deaths
        return tuple(
            int(np.sum((np.asarray(pairs[k])[:, 0] < tau) & (tau <= np.asarray(pairs[k])[:, 1]))) for k in sorted(pairs)
        )

    return [*_generic(v), ("alive on (birth, death]", half_open_left)]


def _bounded_counts(v, ns):
    return [*_generic(v), ("the unbounded component counted too", [int(n) + 1 for n in v])]


def _reduce(v, ns):
    def reduction(pivot, once=False, mod2=True):
        def fn(D):
            R = np.array(D, dtype=np.int64)
            owner = {}
            for j in range(R.shape[1]):
                while R[:, j].any():
                    i = int(pivot(np.flatnonzero(R[:, j])))
                    if i not in owner:
                        owner[i] = j
                        break
                    R[:, j] = (R[:, j] + R[:, owner[i]]) % 2 if mod2 else R[:, j] - R[:, owner[i]]
                    if once:
                        break
            return R

        return fn

    return [
        *_generic(v),
        ("the topmost 1 of a column instead of the lowest", reduction(lambda rows: rows[0])),
        ("at most one addition per column", reduction(lambda rows: rows[-1], once=True)),
        ("columns subtracted over the integers, not mod 2", reduction(lambda rows: rows[-1], mod2=False)),
        (
            "a later column added to an earlier one (same lowest ones, R is not D V)",
            _later_added(reduction(lambda rows: rows[-1])),
        ),
    ]


def _later_added(reduce):
    """Reduce right, then add to each non-zero column the first later one whose lowest one
    is higher up: the lowest ones and D R = 0 survive, R = D V (V upper triangular) does not."""

    def fn(D):
        R = np.asarray(reduce(D)) % 2
        low = [int(np.flatnonzero(c)[-1]) if c.any() else -1 for c in R.T]
        for j in range(R.shape[1]):
            k = next((k for k in range(j + 1, R.shape[1]) if 0 <= low[k] < low[j]), None)
            if k is not None:
                R[:, j] = (R[:, j] + R[:, k]) % 2
        return R

    return fn


def _rank_over_reals(v, ns):
    def real_rank(M):  # Gaussian elimination over the reals, not mod 2
        A = np.asarray(M, dtype=float)
        return int(np.linalg.matrix_rank(A)) if A.size else 0

    return [*_generic(v), ("the rank over the reals", real_rank)]


def _betti_mod2(v, ns):
    return [*_generic(v), ("the Betti numbers over the rationals", (1, 0, 0)), ("β2 off by one", (*v[:2], v[2] + 1))]


def _bounds(v, ns):
    return [*_generic(v), ("every cycle called a boundary", list(ns["cycle"])), ("nothing bounds", [False] * len(v))]


def _flow_order(v, ns):
    def rho(balls, c, weighted):
        z = balls.centers[c]
        w = balls.radii[c] ** 2 if weighted else np.zeros(len(c))
        A = 2 * (z[1:] - z[0])
        b = (z[1:] ** 2).sum(1) - w[1:] - (z[0] ** 2).sum() + w[0]
        y = np.linalg.solve(A, b)
        return float(((y - z[0]) ** 2).sum() - w[0])

    def unweighted(balls, cells):  # the circumradius of the centres: right for one radius only
        return sorted(range(len(cells)), key=lambda n: rho(balls, cells[n], False))

    def reverse(balls, cells):  # downhill: every arrow backwards
        return sorted(range(len(cells)), key=lambda n: -rho(balls, cells[n], True))

    return [
        *_generic(v),
        ("the order given", lambda balls, cells: list(range(len(cells)))),
        ("the circumradius of the centres, weights ignored", unweighted),
        ("the orthosphere's power, largest first", reverse),
    ]


#: ``"lesson stem:name"`` -> ``f(solution's value, the kernel's globals)`` -> [(label, wrong answer)]

# ---- the theory sections (issue 34): the plausible mistakes of each exercise -----------


def _y_max(v, ns):
    z = ns["three"].centers
    circumcentre = np.linalg.solve(2 * (z[1:] - z[0]), (z[1:] ** 2).sum(axis=1) - (z[0] ** 2).sum())
    return [*_generic(v), ("the circumcentre (radii ignored)", circumcentre), ("the centroid", z.mean(axis=0))]


def _f_max(v, ns):
    r = ns["three"].radii
    return [*_generic(v), ("the squared distance, without the weight", v + float(r[0]) ** 2)]


def _triangles(v, ns):
    balls = ns["hexagon"]
    around = np.argsort(np.arctan2(balls.centers[:, 1], balls.centers[:, 0]))

    def fan(first):
        rest = np.roll(around, -int(np.flatnonzero(around == first)[0]))[1:]
        return [[first, int(a), int(b)] for a, b in zip(rest[:-1], rest[1:])]

    return [*_generic(v), ("a fan from the last ball", fan(len(around) - 1)), ("a fan from ball 1", fan(1))]


def _chain_volume(v, ns):
    r = ns["chain"].radii
    balls = 4 / 3 * np.pi * float((r**3).sum())
    return [*_generic(v), ("the balls alone, no lens", balls)]


def _w1(v, ns):
    return [*_generic(v), ("the bottleneck distance", 1.0), ("the 2-Wasserstein distance", float(np.sqrt(1.25)))]


def _wilson(v, ns):
    k, n = ns["k"], ns["n"]
    p = k / n
    half = 1.959964 * np.sqrt(p * (1 - p) / n)
    from scipy.stats import beta

    exact = (float(beta.ppf(0.025, k, n - k + 1)), float(beta.ppf(0.975, k + 1, n - k)))
    return [*_generic(v), ("the Wald interval", (p - half, p + half)), ("the Clopper–Pearson interval", exact)]


OVERRIDES = {
    "02_homology:my_rank_mod2": _rank_over_reals,
    "02_homology:betti_rp2": _betti_mod2,
    "02_homology:bounds": _bounds,
    "03_dual_complex:my_edge": _edge,
    "04_alpha_filtration:is_attached": _attached,
    "04_alpha_filtration:my_edge_time": _edge_time,
    "07_voids:n_bounded": _bounded_counts,
    "08_pockets:my_closes_at": _closes_at,
    "08_pockets:r_closed": _r_closed,
    "09_pocket_flow:my_sinks": _flow_sinks,
    "09_pocket_flow:my_flow_order": _flow_order,
    "06_dual_complex_3d:chis": _chis,
    "10_tunnels:is_closed_chain": _closed_chain,
    "11_persistence:betti_from_pairs": _betti_from_pairs,
    "11_persistence:eps_one_pocket": _eps_one_pocket,
    "11_persistence:my_reduce": _reduce,
    "12_molecule_case_study:pocket_residues": _residues,
    "12_molecule_case_study:most_exposed": _most_exposed,
    "12_molecule_case_study:voids_after": _voids_after,
    "12_molecule_case_study:v_before": _v_before,
    "13_critical_points:viewpoints": _viewpoints,
    "13_critical_points:my_maxima": _maxima,
    "13_critical_points:my_minima": _minima,
    "15_icp:best": _icp_best,
    "15_icp:my_icp_step": _icp_step,
    "17_optimal_rotation:my_rotation": _horn_rotation,
    "19_shape_classification:most_spread": _most_spread,
    "19_shape_classification:spread": _class_spreads,
    "19_shape_classification:rips_gap": _rips_gap,
    "20_binding_sites:first_rank": _first_site_rank,
    "13_critical_points:y_max": _y_max,
    "13_critical_points:f_max": _f_max,
    "06_dual_complex_3d:triangles": _triangles,
    "05_union_measure:chain_volume": _chain_volume,
    "19_shape_classification:w1": _w1,
    "20_binding_sites:interval": _wilson,
}


def mutants(value, key: str, ns: dict) -> list:
    """``[(label, wrong answer), ...]`` for the answer ``value`` of the exercise ``key``
    (``"lesson stem:name"``); ``ns`` is the kernel's namespace.  Raises
    :class:`Unsupported` when no wrong answer can be made."""
    if key in OVERRIDES:
        return OVERRIDES[key](value, ns)
    out = _generic(value)
    if not out:
        raise Unsupported(f"no wrong answer for {key}")
    return out
