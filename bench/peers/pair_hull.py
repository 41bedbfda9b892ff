#!/usr/bin/env python3
"""The convex hull of consecutive footholds of one leg, prototyped with SCIP on an mfp MPS export.

mfp's displacement cost is the stance centre's move, w |C(j) - C(j-n)|^2 (n legs), not a leg's
own move; for a leg's consecutive steps i and j = i + n it is exactly w |px_j - px_i|^2. So a pair
(i, j) carries its own window of the cost. For each such pair and each pair of stones (r, r') that
survives pruning, the extended (Balas) formulation adds a weight lambda_rr' (its sums over r' and
over r are H_ir and H_jr') and copies of every variable that the pair's own rows hold: both feet,
both stance centres (px, py) and both configurations' (sin, cos). Every MPS row whose variables
all lie in that set (ref_ and reach_ rows, dz_, both stones' region_ rows with H -> lambda) is
copied with its bounds scaled by lambda; each copy of (sin, cos) is kept in the hull of its
configuration's yaw arc (`def_` rows of the first steps, whose centre holds only that foot and
fixed start feet, are copied too). On the copies, the window's cost can be written with the
perspective w |P_j - P_i|^2 / lambda, and with --goal-perspective the last feet's goal cost
w |F_j - g lambda|^2 / lambda (each kept at least its original term), solved by tangent cuts
t >= 2 u . d - |u|^2 lambda at u = d0 / l0 (Kelley's loop: each round re-solves and cuts every copy
whose t lies below its perspective; --seed-cuts writes the goal's rows at the stone's corners and
centre at once). The displacement weight is 1 against the goal's 1000, so --no-perspective (the
windows' cost left as it is) loses nothing; see docs/measurements.md (proof11).

  bench/.venv/bin/python bench/peers/pair_hull.py FILE.mps --best OBJ [--rounds 30] [--min-stones 2]
      [--from-step K] [--no-perspective] [--goal-perspective [--seed-cuts]] [--chain] [--single]
      [--lean | --fixed-yaw] [--only-rows PREFIX ...] [--solve-time-limit S]

Prints: the relaxation's objective, the added variables and rows, then per round the objective,
its share of the root gap (to --best, the MPS objective of the best known plan), the cuts and
SCIP's CPU time. A solve stopped at --solve-time-limit prints its dual bound (still a bound).
Diagnostic only: one thread.
"""
import argparse
import math
import re
import sys
import time

from pyscipopt import quicksum

import root_levers
from root_levers import quadratic_objective

INF = 1e19


def load(path):
    """The MPS model with its integers relaxed."""
    return root_levers.load(path, relax=True)


class Instance:
    """The rows, variables and step structure of one relaxed MPS model."""

    def __init__(self, model):
        self.model = model
        self.vars = {v.name: v for v in model.getVars()}
        self.rows = {}
        for c in model.getConss():
            if c.getConshdlrName() == "linear":
                self.rows[c.name] = (model.getLhs(c), model.getValsLinear(c), model.getRhs(c))
        steps = sorted(int(n[2:]) for n in self.vars if re.match(r"x_\d+$", n))
        self.n, self.N = steps[0], steps[-1] + 1
        self.config = {}
        for i in steps:
            sin = [v for v in self.rows[f"ref_x_{i}"][1] if v.startswith("sin_")][0]
            self.config[i] = int(sin[4:])
        self.stones = {i: sorted(int(n.split("_")[2]) for n in self.vars if n.startswith(f"H_{i}_"))
                       for i in steps}
        self.rows_of = {}  # variable -> names of the rows it appears in
        for name, (_, coef, _) in self.rows.items():
            for v in coef:
                self.rows_of.setdefault(v, []).append(name)

    def yaw_range(self, cfg):
        """The union of configuration cfg's yaw segments [rad]."""
        lo, hi = [], []
        k = 0
        while f"seg_lo_{cfg}_{k}" in self.rows:
            binary = f"seg_{cfg}_{k}"
            lo.append(-self.rows[f"seg_lo_{cfg}_{k}"][1].get(binary, 0.0))
            hi.append(-self.rows[f"seg_hi_{cfg}_{k}"][1].get(binary, 0.0))
            k += 1
        if not lo:  # one segment: no binary
            theta = self.vars[f"theta_{cfg}"]
            return theta.getLbGlobal(), theta.getUbGlobal()
        return min(lo), max(hi)

    def stone_box(self, i, r):
        """The stone's (x, y, z) bounds from its region rows (big-M rows a'f + M H <= b + M)."""
        box = [[-INF, INF] for _ in range(3)]
        k = 0
        while f"region_{i}_{r}_{k}" in self.rows:
            _, coef, rhs = self.rows[f"region_{i}_{r}_{k}"]
            b = rhs - coef.get(f"H_{i}_{r}", 0.0)
            axes = [(a, coef[f"{ax}_{i}"]) for a, ax in enumerate("xyz") if f"{ax}_{i}" in coef]
            if len(axes) == 1:
                a, value = axes[0]
                if value > 0:
                    box[a][1] = min(box[a][1], b / value)
                else:
                    box[a][0] = max(box[a][0], b / value)
            k += 1
        return box


def pair_copy_set(inst, i, j):
    names = [f"{a}_{j}" for a in "xyz"] + [f"p{a}_{j}" for a in "xy"]
    names += [f"sin_{inst.config[j]}", f"cos_{inst.config[j]}"]
    if i >= inst.n:
        names += [f"{a}_{i}" for a in "xyz"] + [f"p{a}_{i}" for a in "xy"]
        names += [f"sin_{inst.config[i]}", f"cos_{inst.config[i]}"]
    return [n for n in dict.fromkeys(names) if n in inst.vars]


def pair_rows(inst, i, j, names):
    """Rows all of whose variables are in names, plus both steps' region rows (H read as lambda)."""
    members = set(names)
    found = set()
    for v in names:
        for row in inst.rows_of.get(v, []):
            if row.startswith("region_"):
                continue
            if all(u in members for u in inst.rows[row][1]):
                found.add(row)
    return sorted(found)


def feasible_pair(inst, i, j, r, rr, dxy, dz):
    """False when stones r (step i) and rr (step j) are further apart than the pair's rows allow."""
    if i < inst.n:
        return True
    a, b = inst.stone_box(i, r), inst.stone_box(j, rr)
    for axis, limit in ((0, dxy), (1, dxy), (2, dz)):
        gap = max(b[axis][0] - a[axis][1], a[axis][0] - b[axis][1], 0.0)
        if gap > limit + 1e-9:
            return False
    return True


def move_limits(inst):
    """Per-axis bound on a leg's move from the ref_ and reach_ rows' half widths, and dz_max."""
    ref = inst.rows[f"ref_x_{inst.n}"]
    reach = inst.rows[f"reach_x_{2 * inst.n}"]
    dz = inst.rows[f"dz_{2 * inst.n}"]
    return ref[2] + reach[2], dz[2]


def arc_rows(model, s, c, lam, lo, hi, tangents=7):
    """(s, c) = lambda * a point of the hull of the chords over the yaw range [lo, hi]."""
    rows = 0
    for k in range(tangents):
        phi = lo + (hi - lo) * k / (tangents - 1)
        model.addCons(math.cos(phi) * c + math.sin(phi) * s <= lam)
        rows += 1
    mid, half = (lo + hi) / 2, (hi - lo) / 2
    model.addCons(math.cos(mid) * c + math.sin(mid) * s >= math.cos(half) * lam)
    return rows + 1


def add_pair_family(inst, i, j, dxy, dz, single=False, lean=False, fixed_yaw=False, only_rows=None):
    """The extended formulation of the pair (i, j); returns {(r, rr): (lambda, copies)} and sizes.
    With single, only step j's stone is disjoined (the hull of one step, i's copies free). With lean,
    only the feet's (x, y) are copied, with the stones' (x, y) rows and the move bound |dx|, |dy| <= dxy.
    With fixed_yaw, (sin, cos) are not copied: a row's rotation terms are replaced by their range over
    the (sin, cos) bounds (feet and centres copied, yaws not)."""
    model, V = inst.model, inst.vars
    names = pair_copy_set(inst, i, j)
    rows = pair_rows(inst, i, j, names)
    if lean:
        names = [n for n in names if n[0] in "xy"]
        rows = pair_rows(inst, i, j, names)
    if fixed_yaw:
        names = [n for n in names if not n.startswith(("sin_", "cos_"))]
    if only_rows:
        rows = [row for row in rows if row.startswith(tuple(only_rows))]
    first = inst.stones[i] if i >= inst.n and not single else [None]
    family, nvars, nrows = {}, 0, 0
    for r in first:
        for rr in inst.stones[j]:
            if r is not None and not feasible_pair(inst, i, j, r, rr, dxy, dz):
                continue
            lam = model.addVar(lb=0, ub=1)
            copy = {n: model.addVar(lb=None) for n in names}
            nvars += 1 + len(copy)
            for n, var in copy.items():
                lb, ub = V[n].getLbGlobal(), V[n].getUbGlobal()
                model.addCons(var >= lb * lam)
                model.addCons(var <= ub * lam)
                nrows += 2
            for row in rows:
                lhs, coef, rhs = inst.rows[row]
                expr = quicksum(a * copy[v] for v, a in coef.items() if v in copy)
                rest = [(a * V[v].getLbGlobal(), a * V[v].getUbGlobal()) for v, a in coef.items() if v not in copy]
                low, high = sum(min(p) for p in rest), sum(max(p) for p in rest)
                if lhs > -INF:
                    model.addCons(expr >= (lhs - high) * lam)
                    nrows += 1
                if rhs < INF:
                    model.addCons(expr <= (rhs - low) * lam)
                    nrows += 1
            for step, stone in ((i, r), (j, rr)):
                if stone is None:
                    continue
                k = 0
                while f"region_{step}_{stone}_{k}" in inst.rows:
                    _, coef, rhs = inst.rows[f"region_{step}_{stone}_{k}"]
                    b = rhs - coef.get(f"H_{step}_{stone}", 0.0)
                    k += 1
                    if any(v not in copy for v in coef if not v.startswith("H_")):
                        continue
                    model.addCons(quicksum(a * copy[v] for v, a in coef.items() if not v.startswith("H_")) <= b * lam)
                    nrows += 1
            if lean and i >= inst.n:
                for a in "xy":
                    model.addCons(copy[f"{a}_{j}"] - copy[f"{a}_{i}"] <= dxy * lam)
                    model.addCons(copy[f"{a}_{i}"] - copy[f"{a}_{j}"] <= dxy * lam)
                    nrows += 2
            for step in (i, j):
                cfg = inst.config.get(step) if step >= inst.n else None
                if cfg is not None and f"sin_{cfg}" in copy:
                    lo, hi = inst.yaw_range(cfg)
                    nrows += arc_rows(model, copy[f"sin_{cfg}"], copy[f"cos_{cfg}"], lam, lo, hi)
            family[(r, rr)] = (lam, copy)
    for n in names:
        model.addCons(quicksum(copy[n] for _, copy in family.values()) == V[n])
        nrows += 1
    for step, index in ((i, 0), (j, 1)):
        if step < inst.n or (single and index == 0):
            continue
        for stone in inst.stones[step]:
            weights = [lam for key, (lam, _) in family.items() if key[index] == stone]
            model.addCons(quicksum(weights) == V[f"H_{step}_{stone}"])
            nrows += 1
    if i < inst.n and not single:
        model.addCons(quicksum(lam for lam, _ in family.values()) == 1)
        nrows += 1
    return family, nvars, nrows




def chain_families(inst, windows):
    """Links, per stone s of a step j held by two families (window j and window j + n), the copies of
    j's variables conditioned on s: sum_r X[(r, s)] (window j) = sum_r'' X[(s, r'')] (window j + n)."""
    rows = 0
    for j, family in windows.items():
        k = j + inst.n
        if k not in windows or j < inst.n:
            continue
        own = {f"{a}_{j}" for a in ("x", "y", "z", "px", "py")}
        own |= {f"sin_{inst.config[j]}", f"cos_{inst.config[j]}"}
        in_both = set(next(iter(family.values()))[1]) & set(next(iter(windows[k].values()))[1])
        shared = sorted(own & in_both)
        for s in inst.stones[j]:
            ending = [copy for key, (_, copy) in family.items() if key[1] == s]
            starting = [copy for key, (_, copy) in windows[k].items() if key[0] == s]
            for n in shared:
                inst.model.addCons(quicksum(c[n] for c in ending) == quicksum(c[n] for c in starting))
                rows += 1
    return rows


def goal_terms(terms, linear, N, n):
    """{step: (weight, (gx, gy))} of the goal cost w |f - g|^2 on the last n feet."""
    goals = {}
    for j in range(N - n, N):
        w = [c for a, b, c in terms if a == b == f"x_{j}"][0] / 2
        goals[j] = (w, tuple(-linear.get(f"{a}_{j}", 0.0) / (2 * w) for a in "xy"))
    return goals


def value(model, d):
    coef, const = d
    return const + sum(a * model.getVal(v) for v, a in coef)


def expr(d):
    coef, const = d
    return quicksum(a * v for v, a in coef) + const


def add_perspective(model, family, moves, original, weight, persp, seeds=None):
    """Writes weight * sum_J |d_J|^2 / lambda_J (at least weight * |original|^2) for one cost term;
    seeds(key) lists points u at which a tangent row t >= 2 u.d - |u|^2 lambda is written at once.
    Returns the objective term and the number of added variables and rows."""
    ts, rows = [], 0
    for key, (lam, copy) in family.items():
        t = model.addVar(lb=0)
        ts.append(t)
        d = moves(lam, copy)
        persp.append((t, lam, d))
        for u in seeds(key) if seeds else []:
            model.addCons(t >= quicksum(2 * ua * expr(e) for ua, e in zip(u, d)) - (u[0] ** 2 + u[1] ** 2) * lam)
            rows += 1
    total = model.addVar(lb=0)
    model.addCons(total == quicksum(ts))
    model.addCons(quicksum(e * e for e in original) <= total)
    return weight * total, len(ts) + 1, 2 + rows


def build(path, opts, pairs=True):
    """The relaxation with the pair families of the windows j >= opts.from_step whose pair has a
    step on at least opts.min_stones stones; returns (model, perspective terms, sizes)."""
    model = load(path)
    inst = Instance(model)
    V = inst.vars
    terms = quadratic_objective(path)
    linear = {n: v.getObj() for n, v in V.items() if v.getObj() != 0.0 and n != "qmatrixvar"}
    w = [c for a, b, c in terms if a == b == f"px_{inst.N - 1}"][0] / 2
    goals = goal_terms(terms, linear, inst.N, inst.n)
    dxy, dz = move_limits(inst)
    windows, nvars, nrows = {}, 0, 0
    for j in range(max(inst.n, opts.from_step), inst.N) if pairs else []:
        i = j - inst.n
        if max(len(inst.stones[j]), len(inst.stones[i]) if i >= inst.n else 1) < opts.min_stones:
            continue
        windows[j], v, r = add_pair_family(inst, i, j, dxy, dz, opts.single, opts.lean, opts.fixed_yaw,
                                           opts.only_rows)
        nvars, nrows = nvars + v, nrows + r
    if opts.chain:
        nrows += chain_families(inst, windows)
    model.delCons([c for c in model.getConss() if c.name == "qmatrix"][0])
    goal_persp = opts.goal_perspective and pairs
    skip = lambda a: a.startswith("p") or (goal_persp and a[0] in "xy" and int(a.split("_")[1]) in windows
                                           and int(a.split("_")[1]) in goals)
    quad = quicksum(0.5 * c * V[a] * V[a] for a, b, c in terms if a == b and not skip(a))
    quad += quicksum(c * V[a] * V[b] for a, b, c in terms if a != b and not a.startswith("p"))
    centre = lambda a, k: (V[f"p{a}_{k}"] if k >= inst.n else 0.0)
    objective, persp = [], []
    for j in range(inst.n, inst.N):
        move = [centre(a, j) - centre(a, j - inst.n) for a in "xy"]
        if j in windows and opts.perspective:
            moves = lambda lam, copy, j=j: [([(copy[f"p{a}_{j}"], 1.0)] + ([(copy[f"p{a}_{j - inst.n}"], -1.0)]
                                             if j - inst.n >= inst.n else []), 0.0) for a in "xy"]
            term, v, r = add_perspective(model, windows[j], moves, move, w, persp)
            objective.append(term)
            nvars, nrows = nvars + v, nrows + r
        else:
            quad += w * (move[0] * move[0] + move[1] * move[1])
    for j, (wg, g) in goals.items():
        if not (goal_persp and j in windows):
            continue
        for a, ga in zip("xy", g):
            linear.pop(f"{a}_{j}", None)
        moves = lambda lam, copy, j=j, g=g: [([(copy[f"{a}_{j}"], 1.0), (lam, -ga)], 0.0) for a, ga in zip("xy", g)]
        original = [V[f"{a}_{j}"] - ga for a, ga in zip("xy", g)]
        seeds = None
        if opts.seed_cuts:
            def seeds(key, j=j, g=g):
                box = inst.stone_box(j, key[1])
                xs, ys = (box[0][0], box[0][1]), (box[1][0], box[1][1])
                points = [(x, y) for x in xs for y in ys] + [(sum(xs) / 2, sum(ys) / 2)]
                return [(x - g[0], y - g[1]) for x, y in points]
        term, v, r = add_perspective(model, windows[j], moves, original, wg, persp, seeds)
        objective.append(term - wg * (g[0] ** 2 + g[1] ** 2))
        nvars, nrows = nvars + v, nrows + r
    epigraph = model.addVar(lb=None)
    model.addCons(quad <= epigraph)
    model.setObjective(quicksum(c * V[n] for n, c in linear.items()) + epigraph + quicksum(objective))
    return model, persp, windows, (nvars, nrows)


def kelley(model, persp, rounds, time_limit, tol=1e-6):
    """Tangent cuts t >= (2 d0 / l0) . d - (|d0|^2 / l0^2) lambda until no perspective term is violated;
    yields (round, objective, cuts added before it, CPU seconds, violated terms)."""
    total_cuts = 0
    for rnd in range(rounds + 1):
        start = time.process_time()
        model.setParam("limits/time", time_limit)
        model.optimize()
        seconds = time.process_time() - start
        if model.getStatus() != "optimal":  # a relaxation's dual bound is still a valid bound
            yield rnd, model.getDualbound(), total_cuts, seconds, f"stopped {model.getStatus()}"
            return
        objective = model.getObjVal()
        cuts = []
        for t, lam, d in persp:
            l0 = model.getVal(lam)
            if l0 < 1e-7:
                continue
            d0 = [value(model, e) for e in d]
            f0 = sum(x * x for x in d0) / l0
            if model.getVal(t) < f0 - tol * max(1.0, f0):
                cuts.append((t, lam, d, d0, l0))
        yield rnd, objective, total_cuts, seconds, len(cuts)
        if not cuts or rnd == rounds:
            return
        model.freeTransform()
        for t, lam, d, d0, l0 in cuts:
            model.addCons(t >= quicksum(2 * x / l0 * expr(e) for x, e in zip(d0, d))
                          - sum(x * x for x in d0) / l0 ** 2 * lam)
        total_cuts += len(cuts)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mps")
    parser.add_argument("--best", type=float, help="MPS objective of the best known plan")
    parser.add_argument("--rounds", type=int, default=30)
    parser.add_argument("--min-stones", type=int, default=2)
    parser.add_argument("--solve-time-limit", type=float, default=600.0, help="per relaxation solve [s]")
    parser.add_argument("--from-step", type=int, default=0)
    parser.add_argument("--no-perspective", dest="perspective", action="store_false",
                        help="leave the windows' displacement cost as it is")
    parser.add_argument("--goal-perspective", action="store_true",
                        help="also write the last feet's goal cost in perspective form on the copies")
    parser.add_argument("--single", action="store_true",
                        help="disjoin only the later step of each pair (the hull of one step), for comparison")
    parser.add_argument("--seed-cuts", action="store_true",
                        help="write the goal terms' tangent rows at the stone's corners and centre at once")
    parser.add_argument("--lean", action="store_true",
                        help="copy only the feet's (x, y): stone rows and the move bound, no centres or yaws")
    parser.add_argument("--fixed-yaw", action="store_true",
                        help="copy feet and centres but not (sin, cos): rotation terms bounded by their range")
    parser.add_argument("--only-rows", nargs="+", metavar="PREFIX",
                        help="copy only the pair's rows whose names start so (ref_, reach_, dz_); stones always")
    parser.add_argument("--chain", action="store_true",
                        help="link the two families of a step per stone (copies conditioned on the stone)")
    opts = parser.parse_args(argv)

    share = lambda v: f"{100 * (v - root) / (opts.best - root):6.2f} %" if opts.best is not None else ""
    plain, _, _, _ = build(opts.mps, opts, pairs=False)
    start = time.process_time()
    plain.optimize()
    root = plain.getObjVal()
    print(f"relaxation {root:.4f}  ({plain.getNVars()} variables, {plain.getNConss()} rows, "
          f"{time.process_time() - start:.2f} s CPU)", flush=True)
    model, persp, windows, (nv, nr) = build(opts.mps, opts)
    pairs = sum(len(f) for f in windows.values())
    print(f"pair families on {len(windows)} windows, {pairs} stone pairs: +{nv} variables, +{nr} rows, "
          f"{len(persp)} perspective terms", flush=True)
    for rnd, objective, cuts, seconds, violated in kelley(model, persp, opts.rounds, opts.solve_time_limit):
        print(f"round {rnd:3d}: {objective:.4f}  closes {share(objective)}  cuts so far {cuts:5d}  "
              f"violated {violated!s:>5}  ({seconds:.2f} s CPU)", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
