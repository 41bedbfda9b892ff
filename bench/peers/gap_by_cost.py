#!/usr/bin/env python3
"""Which cost term of an mfp MIQP carries its root gap, measured with SCIP on its MPS export.

Solves the MIQP (or reads a plan from --sol), solves the continuous relaxation, and prints each
cost family's value at both and the difference: goal (the last feet's x_, y_ terms), displacement
(the stance centres' px_, py_ terms), goal yaw (theta_), trims (trim_). Objectives are the MPS
objective (no constant term).

  bench/.venv/bin/python bench/peers/gap_by_cost.py FILE.mps [--sol FILE.sol | --time-limit 300 --write-sol FILE.sol]

With --write-sol the MIQP's plan is written (SCIP's solution format) and checked on a fresh read.
Diagnostic only: one thread.
"""
import argparse
import sys

from pyscipopt import Model

from pair_hull import load, quadratic_objective


def family(name):
    if name.startswith("trim"):
        return "trims"
    if name.startswith("theta"):
        return "goal yaw"
    if name.startswith("p"):
        return "displacement"
    return "goal" if name[0] in "xy" else "other"


def breakdown(terms, linear, value):
    out = {}
    for a, b, c in terms:
        f = family(a)
        out[f] = out.get(f, 0.0) + (0.5 * c * value[a] * value[a] if a == b else c * value[a] * value[b])
    for n, c in linear.items():
        out[family(n)] = out.get(family(n), 0.0) + c * value[n]
    return out


def solve_miqp(path, time_limit, write_sol):
    model = Model()
    model.hideOutput()
    model.setParam("parallel/maxnthreads", 1)
    model.readProblem(path)
    model.setParam("limits/time", time_limit)
    model.optimize()
    print(f"MIQP: {model.getStatus()}, objective {model.getObjVal():.4f}, bound {model.getDualbound():.4f}, "
          f"{model.getSolvingTime():.1f} s wall")
    if write_sol:
        model.writeBestSol(write_sol)
        check = Model()
        check.hideOutput()
        check.readProblem(path)
        sol = check.readSolFile(write_sol)
        print(f"plan written to {write_sol}; feasible on a fresh read: {check.checkSol(sol, completely=True)}")
    return {v.name: model.getVal(v) for v in model.getVars()}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mps")
    parser.add_argument("--sol", help="a plan in SCIP's solution format instead of solving the MIQP")
    parser.add_argument("--time-limit", type=float, default=300.0, help="for the MIQP solve [s]")
    parser.add_argument("--write-sol", help="write the MIQP's plan here")
    args = parser.parse_args(argv)

    relaxed = load(args.mps)
    relaxed.optimize()
    variables = {v.name: v for v in relaxed.getVars()}
    relaxation = {n: relaxed.getVal(v) for n, v in variables.items()}
    if args.sol:
        plan = {n: 0.0 for n in variables}
        with open(args.sol) as f:
            for line in f:
                parts = line.split()
                if len(parts) >= 2 and parts[0] in plan:
                    plan[parts[0]] = float(parts[1])
    else:
        plan = solve_miqp(args.mps, args.time_limit, args.write_sol)
    terms = quadratic_objective(args.mps)
    linear = {n: v.getObj() for n, v in variables.items() if v.getObj() != 0.0 and n != "qmatrixvar"}
    at_root, at_plan = breakdown(terms, linear, relaxation), breakdown(terms, linear, plan)
    print(f"{'family':<14} {'relaxation':>12} {'plan':>12} {'difference':>11}")
    for f in sorted(set(at_root) | set(at_plan)):
        a, b = at_root.get(f, 0.0), at_plan.get(f, 0.0)
        print(f"{f:<14} {a:12.3f} {b:12.3f} {b - a:11.3f}")
    print(f"{'total':<14} {sum(at_root.values()):12.3f} {sum(at_plan.values()):12.3f} "
          f"{sum(at_plan.values()) - sum(at_root.values()):11.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
