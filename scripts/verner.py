"""For the Verner tableau generator (`gen_vern9.py`; Vern7's was removed in 0.2.0): reading a pair's
40-digit coefficients and checking every order condition (one per rooted tree) in 50-digit
arithmetic before anything is written."""

from __future__ import annotations

import sys
from pathlib import Path

from mpmath import mp, mpf
from rust_literals import mat, row

mp.dps = 50


def load(path: Path, stages: int, extended: int, degree: int):
    """(c, a, b, b̂, bi) from a coefficient file (format in its header). Stage `stages` is
    f(t + h, y_new): node 1, coupling b. b̂ is given directly (`bh`) or as b̂ − b (`d`)."""
    c, b = [mpf(0)] * extended, [mpf(0)] * stages
    bh: list | None = None
    d = [mpf(0)] * stages
    a = [[mpf(0)] * extended for _ in range(extended)]
    bi = [[mpf(0)] * degree for _ in range(extended)]
    for line in path.read_text().splitlines():
        f = line.split()
        if not f or f[0].startswith("#"):
            continue
        kind, idx, value = f[0], [int(x) for x in f[1:-1]], mpf(f[-1])
        if kind == "c":
            c[idx[0]] = value
        elif kind == "a":
            a[idx[0]][idx[1]] = value
        elif kind == "b":
            b[idx[0]] = value
        elif kind == "bh":
            bh = bh or [mpf(0)] * stages
            bh[idx[0]] = value
        elif kind == "d":
            d[idx[0]] = value
        elif kind == "bi":
            bi[idx[0]][idx[1]] = value
        else:
            raise ValueError(f"unknown entry {line!r}")
    c[stages] = mpf(1)
    a[stages][:stages] = b
    if bh is None:
        bh = [b[i] + d[i] for i in range(stages)]
    return c, a, b, bh, bi


_TREES: dict[int, list[tuple]] = {1: [()]}


def trees(n: int) -> list[tuple]:
    """The rooted trees of order n, each a sorted tuple of its subtrees."""
    if n not in _TREES:
        found: set[tuple] = set()

        def grow(rest: int, largest: int, kids: list[tuple]) -> None:
            if rest == 0:
                found.add(tuple(sorted(kids)))
                return
            for k in range(min(rest, largest), 0, -1):
                for t in trees(k):
                    grow(rest - k, k, [*kids, t])

        grow(n - 1, n - 1, [])
        _TREES[n] = sorted(found)
    return _TREES[n]


def order(t: tuple) -> int:
    return 1 + sum(order(s) for s in t)


def gamma(t: tuple) -> int:
    g = order(t)
    for s in t:
        g *= gamma(s)
    return g


def phi(t: tuple, a, stages: int) -> list:
    """Per stage i: the elementary weight of the subtrees, Π_children (A Φ(child))_i."""
    v = [mpf(1)] * stages
    for s in t:
        w = phi(s, a, stages)
        v = [v[i] * sum(a[i][j] * w[j] for j in range(stages)) for i in range(stages)]
    return v


def check(tableau, sizes: tuple[int, int, int], orders: tuple[int, int, int], near: str) -> None:
    """Every order condition in 50 digits: row sums c, b to order q, b̂ to order q̂, the
    interpolant to order p at several σ, and its order-(p + 1) conditions within `near`
    (as published). `sizes` = (stages, extended, degree), `orders` = (q, q̂, p)."""
    c, a, b, bh, bi = tableau
    stages, extended, degree = sizes
    q, qh, p = orders
    for i in range(extended):
        assert abs(sum(a[i]) - c[i]) < mpf(10) ** -35, f"row sum of stage {i}"
    worst = {}
    for n in range(1, p + 2):
        for t in trees(n):
            ph = phi(t, a, stages)
            for name, w, top in (("b", b, q), ("bh", bh, qh)):
                if n <= top:
                    r = abs(sum(w[i] * ph[i] for i in range(stages)) - mpf(1) / gamma(t))
                    assert r < mpf(10) ** -35, f"{name}: tree {t} of order {n} fails by {r}"
            pe = phi(t, a, extended)
            for sigma in (mpf(1) / 7, mpf(1) / 3, mpf("0.7"), mpf(1)):
                weights = [
                    sum(bi[i][j] * sigma ** (j + 1) for j in range(degree)) for i in range(extended)
                ]
                r = abs(sum(weights[i] * pe[i] for i in range(extended)) - sigma**n / gamma(t))
                worst[n] = max(worst.get(n, 0), r)
    for n in range(1, p + 1):
        assert worst[n] < mpf(10) ** -35, f"interpolant order {n}: {worst[n]}"
    assert worst[p + 1] < mpf(near), f"interpolant order {p + 1}: {worst[p + 1]}"
    print(
        f"// order conditions met; interpolant order {p + 1} within {mp.nstr(worst[p + 1], 2)}",
        file=sys.stderr,
    )


def items(tableau, sizes: tuple[int, int, int], orders: tuple[int, int]):
    """The Rust constants of a pair, as (doc, name, type, value) for `rust_literals.const`:
    b − b̂ is formed in 50 digits and rounded once. `orders` = (q, q̂)."""
    c, a, b, bh, bi = tableau
    s, se, deg = sizes
    q, qh = orders
    extra = se - s - 1
    e = [b[i] - bh[i] for i in range(s)] + [mpf(0)]
    r = [[bi[i][j] for i in range(se)] for j in range(deg)]
    return [
        (f"Stages of one step (the FSAL derivative at the step end is stored as stage {s}).",
         "N_STAGES", "usize", str(s)),
        (f"Stages including the {extra} extra ones of the degree-{deg} interpolant.",
         "N_STAGES_EXTENDED", "usize", str(se)),
        ("Order of the propagated solution.", "ORDER", "i32", str(q)),
        (f"Order of the error estimator; step control uses the exponent −1/({qh} + 1).",
         "ERROR_ESTIMATOR_ORDER", "i32", str(qh)),
        ("Step-size exponent −1/(error_estimator_order + 1).",
         "ERROR_EXPONENT", "f64", "-1.0 / (ERROR_ESTIMATOR_ORDER as f64 + 1.0)"),
        (f"Nodes c_i of the {s} main stages.", "C", "[f64; N_STAGES]", row(c[:s])),
        ("Stage coupling a_ij of the main stages (row i, columns j < i; zero-padded).",
         "A", "[[f64; N_STAGES]; N_STAGES]", mat([r_[:s] for r_ in a[:s]])),
        (f"Weights of the order-{q} solution.", "B", "[f64; N_STAGES]", row(b)),
        (f"Error weights b − b̂ over the {s + 1} stages (including FSAL, whose weight is 0).",
         "E", "[f64; N_STAGES + 1]", row(e)),
        ("Nodes of the extra stages of the interpolant.",
         "C_EXTRA", f"[f64; {extra}]", row(c[s + 1 :])),
        (f"Coupling of the extra stages to the {s + 1} before them (and to each other).",
         "A_EXTRA", f"[[f64; N_STAGES_EXTENDED]; {extra}]", mat(a[s + 1 :])),
        ("The interpolant y(t + σh) = y + h Σ_j σ^(j+1) Σ_i R_ji K_i (row j: σ^(j+1)).",
         "R", f"[[f64; N_STAGES_EXTENDED]; {deg}]", mat(r)),
    ]  # fmt: skip
