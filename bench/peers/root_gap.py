#!/usr/bin/env python3
"""Where the root gap of an mfp MIQP comes from, measured with SCIP on its MPS export.

Solves the MIQP to optimality, then the continuous relaxation with no integers fixed
(the root bound), and with each family of integer variables (named by the prefix of
their MPS column names: H = regions, seg = yaw segments, trim = trimming) fixed to
its optimal values, alone and in pairs. Prints one line per case: the relaxation's
objective and the share of the root gap that fixing that family closes.

  bench/.venv/bin/python bench/peers/root_gap.py FILE.mps [--time-limit 300]

Objectives are the MPS objective (no constant term). Diagnostic only: one thread, no
timing is reported.
"""
import argparse
import itertools
import re
import sys

from pyscipopt import Model


def load(path):
    model = Model()
    model.hideOutput()
    model.setParam("parallel/maxnthreads", 1)
    model.readProblem(path)
    return model


def family(name):
    return re.sub(r"[\d_\[\]]+$", "", name)


def relaxation(path, optimum, fixed_families):
    model = load(path)
    for var in model.getVars():
        if var.vtype() in ("BINARY", "INTEGER"):
            model.chgVarType(var, "CONTINUOUS")
            if family(var.name) in fixed_families:
                model.fixVar(var, round(optimum[var.name]))
    model.optimize()
    if model.getStatus() != "optimal":
        raise RuntimeError(f"relaxation with {sorted(fixed_families)} fixed ended {model.getStatus()}")
    return model.getObjVal()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mps")
    parser.add_argument("--time-limit", type=float, default=300.0, help="for the MIQP solve [s]")
    parser.add_argument("--accept-incumbent", action="store_true",
                        help="when the MIQP is not proven in the time limit, fix families at SCIP's best "
                             "plan instead (the gap is then measured against that plan)")
    args = parser.parse_args(argv)

    model = load(args.mps)
    model.setParam("limits/time", args.time_limit)
    model.optimize()
    if model.getStatus() != "optimal":
        if not (args.accept_incumbent and model.getNSols() > 0):
            print(f"{args.mps}: the MIQP was not solved to optimality ({model.getStatus()})", file=sys.stderr)
            return 3
        print(f"{args.mps}: not proven ({model.getStatus()}); families fixed at the best plan found")
    optimum = {var.name: model.getVal(var) for var in model.getVars()}
    best = model.getObjVal()
    families = sorted({family(v.name) for v in model.getVars() if v.vtype() in ("BINARY", "INTEGER")})

    root = relaxation(args.mps, optimum, set())
    print(f"optimum {best:.4f}  root bound {root:.4f}  root gap {best - root:.4f}")
    cases = [set()] + [{f} for f in families] + [set(pair) for pair in itertools.combinations(families, 2)]
    cases.append(set(families))
    for fixed in cases[1:]:
        value = relaxation(args.mps, optimum, fixed)
        closed = (value - root) / (best - root) if best > root else 1.0
        print(f"fixed {'+'.join(sorted(fixed)):<16} relaxation {value:.4f}  closes {100 * closed:5.1f} % of the gap")
    return 0


if __name__ == "__main__":
    sys.exit(main())
