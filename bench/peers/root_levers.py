#!/usr/bin/env python3
"""Root-bound levers of an mfp MIQP prototyped with SCIP on its MPS export, before building them.

Three measurements, each printed as one line per case (objectives are the MPS objective,
without the JSON's objective_offset):

  yaw-pairs    the continuous relaxation, then the same with the extended (Balas) formulation of
               every pair of consecutive configurations' yaw segments added: a weight per
               segment pair whose yaw ranges can be within the yaw change limit, the pair's own
               copies of both yaws inside their segments and within the limit of each other,
               summing to the segment binaries and the per-segment yaw copies of the hull encoding.
  perspective  the continuous relaxation, then the same with the goal-position cost of the last
               n feet written in its perspective form over the foot's region choice (hull copies
               F_r of the foot, A_r F_r <= b_r H_r, cost w |F_r - g H_r|^2 / H_r). SCIP treats the
               cones as nonconvex, so the second case prints its primal value (an upper bound on
               the perspective relaxation's optimum: what it can gain at most) and its dual bound.
  separators   SCIP's root (node limit 1, no restarts) with cut separators switched off, only
               aggregation c-MIR, only Gomory, or all. SCIP's dual bound at the node limit also
               holds its root strong branching, common to every case.
  scip-cuts    the continuous relaxation with the cuts of SCIP's root LP added as rows (root
               without presolve or heuristics, so the cuts are on the original variables; cuts
               on SCIP's auxiliary variables of the objective cannot be carried over and are left
               out): what mfp's QP relaxation would gain from the cuts SCIP finds.

  bench/.venv/bin/python bench/peers/root_levers.py yaw-pairs|perspective|separators|scip-cuts FILE.mps [--legs 4]

Diagnostic only: one thread; no timing is reported.
"""
import argparse
import math
import re
import sys

from pyscipopt import SCIP_PARAMSETTING, Model, quicksum


def load(path, relax):
    model = Model()
    model.hideOutput()
    model.setParam("parallel/maxnthreads", 1)
    model.readProblem(path)
    if relax:
        for var in model.getVars():
            if var.vtype() in ("BINARY", "INTEGER"):
                model.chgVarType(var, "CONTINUOUS")
    return model


def yaw_segments(model):
    """{configuration: {segment: (lo, hi, binary, yaw copy)}} read from the seg_lo/seg_hi rows."""
    variables = {v.name: v for v in model.getVars()}
    rows = {c.name: c for c in model.getConss()}
    segments = {}
    for name, row in rows.items():
        match = re.match(r"seg_lo_(\d+)_(\d+)$", name)
        if not match:
            continue
        cfg, k = int(match.group(1)), int(match.group(2))
        binary = f"seg_{cfg}_{k}"
        lo = -model.getValsLinear(row).get(binary, 0.0)
        hi = -model.getValsLinear(rows[f"seg_hi_{cfg}_{k}"]).get(binary, 0.0)
        segments.setdefault(cfg, {})[k] = (lo, hi, variables[binary], variables[f"theta_{cfg}_{k}"])
    return segments


def add_yaw_pairs(model, segments, limit):
    """Adds the extended formulation of consecutive configurations' segment pairs; returns the pairs."""
    pairs = 0
    for cfg in sorted(segments):
        if cfg + 1 not in segments:
            continue
        first, second = segments[cfg], segments[cfg + 1]
        weights = {k: [] for k in first}, {l: [] for l in second}
        copies = {k: [] for k in first}, {l: [] for l in second}
        for k, (a, e, _, _) in first.items():
            for l, (a2, e2, _, _) in second.items():
                if a2 - e > limit + 1e-9 or a - e2 > limit + 1e-9:
                    continue
                z, u, v = model.addVar(lb=0, ub=1), model.addVar(lb=None), model.addVar(lb=None)
                model.addCons(u >= a * z)
                model.addCons(u <= e * z)
                model.addCons(v >= a2 * z)
                model.addCons(v <= e2 * z)
                model.addCons(v - u <= limit * z)
                model.addCons(u - v <= limit * z)
                weights[0][k].append(z)
                weights[1][l].append(z)
                copies[0][k].append(u)
                copies[1][l].append(v)
                pairs += 1
        for side, segs in enumerate((first, second)):
            for k, (_, _, binary, yaw_copy) in segs.items():
                model.addCons(quicksum(weights[side][k]) == binary)
                model.addCons(quicksum(copies[side][k]) == yaw_copy)
    return pairs


def yaw_pairs(path, _legs):
    plain = load(path, relax=True)
    plain.optimize()
    norms = lambda m: " ".join(f"{math.hypot(m.getVal(s), m.getVal(c)):.3f}" for s, c in sin_cos(m))
    print(f"relaxation {plain.getObjVal():.4f}  |(sin, cos)| per configuration {norms(plain)}")
    model = load(path, relax=True)
    segments = yaw_segments(model)
    limit = model.getRhs([c for c in model.getConss() if c.name.startswith("yaw_change_")][-1])
    pairs = add_yaw_pairs(model, segments, limit)
    model.optimize()
    print(f"with yaw pairs {model.getObjVal():.4f} (+{model.getObjVal() - plain.getObjVal():.4f}, {pairs} pairs, "
          f"yaw change limit {limit:.4f} rad)  |(sin, cos)| {norms(model)}")


def sin_cos(model):
    variables = {v.name: v for v in model.getVars()}
    cfgs = sorted(int(n.split("_")[1]) for n in variables if re.match(r"sin_\d+$", n))
    return [(variables[f"sin_{c}"], variables[f"cos_{c}"]) for c in cfgs]


def quadratic_objective(path):
    terms, section = [], None
    with open(path) as f:
        for line in f:
            if not line.startswith(" "):
                section = line.split()[0] if line.strip() else section
            elif section == "QUADOBJ":
                a, b, value = line.split()
                terms.append((a, b, float(value)))
    return terms


def perspective_model(path, legs, perspective):
    """The relaxation with its objective rebuilt from the MPS (x'Qx/2 + c'x); with perspective, the
    last legs feet's goal terms are replaced by their perspective over the region choice."""
    model = load(path, relax=True)
    variables = {v.name: v for v in model.getVars()}
    rows = {c.name: c for c in model.getConss()}
    terms = quadratic_objective(path)
    steps = sorted(int(n.split("_")[1]) for n in variables if re.match(r"x_\d+$", n))
    last = steps[-legs:] if perspective else []
    goal_vars = {f"{axis}_{i}" for i in last for axis in "xy"}
    model.delCons(rows["qmatrix"])
    linear = {n: v.getObj() for n, v in variables.items() if v.getObj() != 0.0 and n != "qmatrixvar"}
    quadratic = quicksum(0.5 * c * variables[a] * variables[a] for a, b, c in terms if a == b and a not in goal_vars)
    quadratic += quicksum(c * variables[a] * variables[b] for a, b, c in terms if a != b)
    constant, cones = 0.0, []
    for i in last:
        weight = [c for a, b, c in terms if a == b == f"x_{i}"][0] / 2
        goal = {axis: -variables[f"{axis}_{i}"].getObj() / (2 * weight) for axis in "xy"}
        for axis in "xy":
            linear.pop(f"{axis}_{i}", None)
            constant -= weight * goal[axis] ** 2
        sums = {axis: [] for axis in "xyz"}
        for r in sorted({n.split("_")[2] for n in variables if n.startswith(f"H_{i}_")}):
            h = variables[f"H_{i}_{r}"]
            copy = {axis: model.addVar(lb=None) for axis in "xyz"}
            for axis in "xyz":
                model.addCons(copy[axis] >= variables[f"{axis}_{i}"].getLbGlobal() * h)
                model.addCons(copy[axis] <= variables[f"{axis}_{i}"].getUbGlobal() * h)
                sums[axis].append(copy[axis])
            k = 0
            while f"region_{i}_{r}_{k}" in rows:  # big-M row a'f + M H <= b + M
                row = rows[f"region_{i}_{r}_{k}"]
                coef = model.getValsLinear(row)
                b = model.getRhs(row) - coef.get(f"H_{i}_{r}", 0.0)
                model.addCons(quicksum(coef.get(f"{axis}_{i}", 0.0) * copy[axis] for axis in "xyz") <= b * h)
                k += 1
            tau = model.addVar(lb=0)
            model.addCons((copy["x"] - goal["x"] * h) ** 2 + (copy["y"] - goal["y"] * h) ** 2 <= tau * h)
            cones.append(weight * tau)
        for axis in "xyz":
            model.addCons(quicksum(sums[axis]) == variables[f"{axis}_{i}"])
    epigraph = model.addVar(lb=None)
    model.addCons(quadratic + quicksum(cones) + constant <= epigraph)
    model.setObjective(quicksum(c * variables[n] for n, c in linear.items()) + epigraph)
    return model


def perspective(path, legs, time_limit=150.0):
    plain = perspective_model(path, legs, perspective=False)
    plain.optimize()
    print(f"relaxation {plain.getObjVal():.4f}")
    model = perspective_model(path, legs, perspective=True)
    model.setParam("limits/time", time_limit)
    model.optimize()
    print(f"with the goal perspective ({model.getStatus()}): at most {model.getPrimalbound():.4f} "
          f"(+{model.getPrimalbound() - plain.getObjVal():.4f}), dual bound {model.getDualbound():.4f}")


SEPARATORS = ["aggregation", "gomory", "impliedbounds", "clique", "flowcover", "knapsackcover", "zerohalf", "mcf",
              "mixing", "disjunctive", "cgmip", "oddcycle", "rapidlearning", "rlt", "minor", "convexproj", "gauge",
              "interminor"]


def separators(path, _legs, time_limit=300.0):
    for name, only in (("none", []), ("only aggregation", ["aggregation"]), ("only gomory", ["gomory"]),
                       ("all", None)):
        model = load(path, relax=False)
        model.setParam("limits/nodes", 1)
        model.setParam("limits/time", time_limit)
        model.setParam("presolving/maxrestarts", 0)
        if only is not None:
            for sepa in SEPARATORS:
                try:
                    model.setParam(f"separating/{sepa}/freq", 10 if sepa in only else -1)
                except KeyError:
                    pass  # a separator this SCIP does not have
        model.optimize()
        print(f"separators {name:<18} root dual bound {model.getDualbound():.4f}", flush=True)


def scip_cuts(path, _legs):
    root = load(path, relax=False)
    root.setParam("limits/nodes", 1)
    root.setParam("presolving/maxrestarts", 0)
    root.setPresolve(SCIP_PARAMSETTING.OFF)
    root.setHeuristics(SCIP_PARAMSETTING.OFF)
    root.optimize()
    original = {v.name for v in root.getVars()} - {"qmatrixvar"}
    rows = {c.name for c in root.getConss()}
    cuts = []
    for row in root.getLPRowsData():
        names = [c.getVar().name.removeprefix("t_") for c in row.getCols()]
        if not row.name or row.name in rows or any(n not in original for n in names):
            continue
        cuts.append((names, row.getVals(), row.getLhs() - row.getConstant(), row.getRhs() - row.getConstant()))
    plain = load(path, relax=True)
    plain.optimize()
    model = load(path, relax=True)
    variables = {v.name: v for v in model.getVars()}
    for names, values, lhs, rhs in cuts:
        expr = quicksum(a * variables[n] for n, a in zip(names, values))
        if lhs > -1e19:
            model.addCons(expr >= lhs)
        if rhs < 1e19:
            model.addCons(expr <= rhs)
    model.optimize()
    print(f"SCIP's root {root.getDualbound():.4f} (with its strong branching); relaxation {plain.getObjVal():.4f}, "
          f"with SCIP's {len(cuts)} cuts on original variables {model.getObjVal():.4f} "
          f"(+{model.getObjVal() - plain.getObjVal():.4f})")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("lever", choices=["yaw-pairs", "perspective", "separators", "scip-cuts"])
    parser.add_argument("mps")
    parser.add_argument("--legs", type=int, default=4, help="feet whose goal cost the perspective rewrites")
    args = parser.parse_args(argv)
    {"yaw-pairs": yaw_pairs, "perspective": perspective, "separators": separators,
     "scip-cuts": scip_cuts}[args.lever](args.mps, args.legs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
