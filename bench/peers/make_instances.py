#!/usr/bin/env python3
"""Writes generated MPS test instances for the peer bench (no solver needed).

    make_instances.py binary  OUT.mps [--n 12] [--seed 1]
        A pure-binary convex MIQP whose optimum is found here by enumerating all 2^n
        assignments in exact rational arithmetic; the optimum goes to OUT.json as
        "known_mps_objective".
    make_instances.py stones  OUT.mps [--steps 8] [--stones 4] [--seed 1]
        A footstep-like MIQP: one foot steps from (0, 0) towards a goal over box-shaped
        stepping stones; big-M region binaries, ranged step-length rows, a quadratic
        cost on step displacement and on the final distance to the goal (off-diagonal
        QUADOBJ terms). Variables = steps*(2+stones), rows = steps*(3+4*stones).
        The constant term goes to OUT.json as "objective_offset", as mfp does.

Both write free MPS with QUADOBJ listing each upper-triangle entry of Q once
(objective = c'x + 0.5 x'Qx), binaries inside MARKER INTORG/INTEND with BV bounds.
"""

import argparse
import itertools
import json
import random
from fractions import Fraction


def write_mps(path, name, rows, columns, rhs, ranges, bounds, quad):
    """rows: [(name, 'E'|'L'|'G')]; columns: [(col, integer, {row: coef})] with the
    objective row named 'obj'; rhs / ranges: {row: value}; bounds: [(type, col, value)];
    quad: [(col_i, col_j, q_ij)] upper triangle, each entry once."""
    out = [f"NAME {name}", "ROWS", " N obj"]
    out += [f" {sense} {row}" for row, sense in rows]
    out.append("COLUMNS")
    in_int = False
    marker = 0
    for col, integer, coefs in columns:
        if integer and not in_int:
            marker += 1
            out.append(f" M{marker} 'MARKER' 'INTORG'")
            in_int = True
        elif not integer and in_int:
            out.append(f" M{marker} 'MARKER' 'INTEND'")
            in_int = False
        if not coefs:
            coefs = {"obj": 0}
        for row, value in coefs.items():
            out.append(f" {col} {row} {fmt(value)}")
    if in_int:
        out.append(f" M{marker} 'MARKER' 'INTEND'")
    out.append("RHS")
    out += [f" rhs {row} {fmt(v)}" for row, v in rhs.items() if v != 0]
    if ranges:
        out.append("RANGES")
        out += [f" rng {row} {fmt(v)}" for row, v in ranges.items()]
    out.append("BOUNDS")
    for kind, col, value in bounds:
        out.append(f" {kind} bnd {col}" + ("" if value is None else f" {fmt(value)}"))
    if quad:
        out.append("QUADOBJ")
        out += [f" {i} {j} {fmt(q)}" for i, j, q in quad if q != 0]
    out.append("ENDATA")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def fmt(value):
    return repr(float(value)) if not isinstance(value, int) else str(value)


def make_binary(path, n, seed):
    rng = random.Random(seed)
    # Q = L L' + I with small integer L: positive definite, integer entries.
    k = 3
    L = [[rng.randint(-2, 2) for _ in range(k)] for _ in range(n)]
    Q = [[sum(L[i][t] * L[j][t] for t in range(k)) + (1 if i == j else 0) for j in range(n)] for i in range(n)]
    c = [rng.randint(-9, 3) for _ in range(n)]
    w = [rng.randint(1, 6) for _ in range(n)]
    cap = sum(w) // 2
    names = [f"b{i}" for i in range(n)]
    # rows: knapsack sum w_i b_i <= cap; cover sum b_i >= 3; exactly one of b0, b1.
    columns = []
    for i in range(n):
        coefs = {"obj": c[i], "knap": w[i], "cover": 1}
        if i < 2:
            coefs["pick"] = 1
        columns.append((names[i], True, coefs))
    rows = [("knap", "L"), ("cover", "G"), ("pick", "E")]
    rhs = {"knap": cap, "cover": 3, "pick": 1}
    bounds = [("BV", nm, None) for nm in names]
    quad = [(names[i], names[j], Q[i][j]) for i in range(n) for j in range(i, n)]
    write_mps(path, f"binary{n}", rows, columns, rhs, {}, bounds, quad)

    best = None
    for bits in itertools.product((0, 1), repeat=n):
        if sum(w[i] * bits[i] for i in range(n)) > cap or sum(bits) < 3 or bits[0] + bits[1] != 1:
            continue
        value = Fraction(sum(c[i] * bits[i] for i in range(n)))
        value += Fraction(sum(Q[i][j] * bits[i] * bits[j] for i in range(n) for j in range(n)), 2)
        if best is None or value < best[0]:
            best = (value, bits)
    return {"known_mps_objective": float(best[0]), "known_solution": dict(zip(names, best[1])),
            "objective_offset": 0.0, "source": f"enumeration of 2^{n} assignments (make_instances.py)"}


def make_stones(path, steps, stones, seed):
    rng = random.Random(seed)
    d_max = 0.35          # largest step along x or y (m)
    goal = (0.3 * steps * 0.8, 0.1)
    w_goal = 10.0
    # Stones: boxes spread along the way to the goal, gaps narrower than a step.
    boxes = []
    x = -0.2
    for r in range(stones):
        half_x = rng.uniform(0.08, 0.2)
        half_y = rng.uniform(0.1, 0.3)
        cy = rng.uniform(-0.2, 0.3)
        cx = x + half_x
        boxes.append((cx - half_x, cx + half_x, cy - half_y, cy + half_y))
        x = cx + half_x + rng.uniform(0.05, 0.2)
    span = max(goal[0], x) + 1.0
    big_m = 2 * span + 2.0
    columns, rows, rhs, ranges, bounds, quad = [], [], {}, {}, [], []
    qdiag = {}
    lin = {}

    def var(axis, i):
        return f"{axis}{i}"

    # Start foot fixed at the first stone's centre by bounds.
    x0, y0 = (boxes[0][0] + boxes[0][1]) / 2, (boxes[0][2] + boxes[0][3]) / 2
    col_coefs = {}
    for i in range(steps + 1):
        for axis in "xy":
            col_coefs[var(axis, i)] = {}
    for i in range(1, steps + 1):
        for axis in "xy":
            # ranged row: -d_max <= p_i - p_{i-1} <= d_max
            row = f"s{axis}{i}"
            rows.append((row, "L"))
            rhs[row] = d_max
            ranges[row] = 2 * d_max
            col_coefs[var(axis, i)][row] = 1
            col_coefs[var(axis, i - 1)][row] = -1
            # cost (p_i - p_{i-1})^2 = 0.5 * (2 p_i^2 + 2 p_{i-1}^2 - 4 p_i p_{i-1})
            qdiag[var(axis, i)] = qdiag.get(var(axis, i), 0) + 2
            qdiag[var(axis, i - 1)] = qdiag.get(var(axis, i - 1), 0) + 2
            quad.append((var(axis, i - 1), var(axis, i), -2.0))
        sos = f"one{i}"
        rows.append((sos, "E"))
        rhs[sos] = 1
        for r, (xl, xu, yl, yu) in enumerate(boxes):
            h = f"h{i}_{r}"
            coefs = {sos: 1}
            # H => xl <= x_i <= xu, yl <= y_i <= yu, as big-M rows
            for axis, lo, hi in (("x", xl, xu), ("y", yl, yu)):
                up, dn = f"u{axis}{i}_{r}", f"d{axis}{i}_{r}"
                rows.append((up, "L"))      # p - hi + M h <= M
                rows.append((dn, "G"))      # p - lo - M h >= -M
                col_coefs[var(axis, i)][up] = 1
                col_coefs[var(axis, i)][dn] = 1
                coefs[up] = big_m
                coefs[dn] = -big_m
                rhs[up] = hi + big_m
                rhs[dn] = lo - big_m
            columns.append((h, True, coefs))
            bounds.append(("BV", h, None))
    # Goal term w * |p_N - goal|^2 = w p_N^2 - 2 w goal p_N + w |goal|^2 (constant dropped).
    for axis, g in (("x", goal[0]), ("y", goal[1])):
        qdiag[var(axis, steps)] += 2 * w_goal
        lin[var(axis, steps)] = -2 * w_goal * g
    offset = w_goal * (goal[0] ** 2 + goal[1] ** 2)
    continuous = []
    for i in range(steps + 1):
        for axis in "xy":
            name = var(axis, i)
            coefs = dict(col_coefs[name])
            if name in lin:
                coefs = {"obj": lin[name], **coefs}
            continuous.append((name, False, coefs))
            if i == 0:
                bounds.append(("FX", name, x0 if axis == "x" else y0))
            else:
                bounds.append(("FR", name, None))
    quad = [(v, v, q) for v, q in qdiag.items()] + quad
    write_mps(path, f"stones{steps}x{stones}", rows, continuous + columns, rhs, ranges, bounds, quad)
    return {"objective_offset": offset, "integer_variables": steps * stones,
            "source": f"make_instances.py stones --steps {steps} --stones {stones} --seed {seed}"}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="kind", required=True)
    b = sub.add_parser("binary")
    b.add_argument("out")
    b.add_argument("--n", type=int, default=12)
    b.add_argument("--seed", type=int, default=1)
    s = sub.add_parser("stones")
    s.add_argument("out")
    s.add_argument("--steps", type=int, default=8)
    s.add_argument("--stones", type=int, default=4)
    s.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    if not args.out.endswith(".mps"):
        parser.error("OUT must end in .mps (the JSON goes beside it)")
    if args.kind == "binary":
        if not 1 <= args.n <= 20:
            parser.error("--n must be in [1, 20] (enumeration)")
        meta = make_binary(args.out, args.n, args.seed)
    else:
        if args.steps < 1 or args.stones < 2:
            parser.error("--steps >= 1 and --stones >= 2")
        meta = make_stones(args.out, args.steps, args.stones, args.seed)
    with open(args.out[:-4] + ".json", "w") as f:
        json.dump(meta, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
