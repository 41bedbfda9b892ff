#!/usr/bin/env python3
"""Self-test of the peer bench: every available peer must read the MPS files the same way.

1. Known optima: each instances/NAME.mps whose NAME.json has "known_status" (worked out
   by hand in the file's comments, or by enumeration) must be solved by every available
   peer with that status and, when optimal, that objective (1e-4 absolute + relative).
2. Agreement: a generated footstep-like instance (make_instances.py stones, 8 steps x 4
   stones, off-diagonal QUADOBJ, ranged rows, FR / FX bounds): all peers must prove
   optimality and agree with each other.
   Instances with RANGES are solved a second time with --split-ranges (each ranged
   row given as two rows), which must not change the answer.
3. Licence sizes: generated instances above Gurobi's (200 variables, quadratic objective)
   and CPLEX's and COPT's size limits: a peer must either solve or report "refused";
   "error" fails. What each did is printed.

A peer that is not installed is "skipped", not failed; the summary says which.
Ends with the line "N passed, N failed" and exits non-zero when anything failed.
"""

import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SOLVERS = ("scip", "copt", "cplex", "gurobi", "bonmin")
ABS_TOL = 1e-4
REL_TOL = 1e-4


def close(a, b):
    return abs(a - b) <= ABS_TOL + REL_TOL * max(abs(a), abs(b))


def has_ranges(mps):
    with open(mps) as f:
        return any(line.split()[:1] == ["RANGES"] for line in f)


def solve(python, solver, mps, time_limit, extra=()):
    cmd = [python, os.path.join(HERE, "solve_mps.py"), "--solver", solver, mps,
           "--time-limit", str(time_limit), "--threads", "1", *extra]
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                          timeout=time_limit * 2 + 60, check=False)
    lines = [ln for ln in proc.stdout.splitlines() if ln.startswith("{")]
    if not lines:
        return {"status": "error", "message": f"solve_mps.py exited {proc.returncode} without a result"}
    return json.loads(lines[-1])


class Tally:
    def __init__(self):
        self.passed = 0
        self.failed = 0
        self.skipped = set()

    def check(self, ok, label, detail):
        if ok:
            self.passed += 1
        else:
            self.failed += 1
        print(f"{'ok  ' if ok else 'FAIL'} {label}: {detail}", flush=True)


def describe(r):
    obj = r.get("objective")
    text = r["status"] + ("" if obj is None else f" obj {obj:.9g}")
    if r.get("time_s") is not None:
        text += f" in {r['time_s']:.3g} s"
    if r["status"] in ("refused", "error", "unavailable") and r.get("message"):
        text += f" ({r['message']})"
    return text


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--python", default=sys.executable, help="interpreter with the solver packages")
    parser.add_argument("--solvers", default=",".join(SOLVERS))
    args = parser.parse_args()
    solvers = [s for s in args.solvers.split(",") if s]
    tally = Tally()

    def run(solver, mps, time_limit):
        r = solve(args.python, solver, mps, time_limit)
        if r["status"] == "unavailable":
            tally.skipped.add(f"{solver} ({r.get('message', '')})")
        return r

    # 1. Known optima.
    for mps in sorted(glob.glob(os.path.join(HERE, "instances", "*.mps"))):
        with open(mps[:-4] + ".json") as f:
            known = json.load(f)
        if "known_status" not in known:
            continue
        name = os.path.basename(mps)
        for solver in solvers:
            r = run(solver, mps, 30)
            if r["status"] == "unavailable":
                continue
            ok = r["status"] == known["known_status"]
            if ok and known["known_status"] == "optimal":
                ok = r.get("objective") is not None and close(r["objective"], known["known_mps_objective"])
            want = known["known_status"] + ("" if known.get("known_mps_objective") is None
                                            else f" obj {known['known_mps_objective']:.9g}")
            tally.check(ok, f"{name} {solver}", f"{describe(r)}; known: {want}")
            if ok and has_ranges(mps):
                # The same problem with ranged rows as pairs of rows (--split-ranges).
                r = solve(args.python, solver, mps, 30, ["--split-ranges"])
                same = r["status"] == known["known_status"] and (
                    known["known_status"] != "optimal"
                    or (r.get("objective") is not None and close(r["objective"], known["known_mps_objective"])))
                tally.check(same, f"{name} {solver} --split-ranges", describe(r))

    with tempfile.TemporaryDirectory(prefix="mfp_peers_selftest_") as tmp:
        # 2. Agreement on a generated footstep-like instance.
        mps = os.path.join(tmp, "stones8x4.mps")
        subprocess.run([sys.executable, os.path.join(HERE, "make_instances.py"), "stones", mps,
                        "--steps", "8", "--stones", "4"], check=True)
        results = {}
        for solver in solvers:
            r = run(solver, mps, 60)
            if r["status"] != "unavailable":
                results[solver] = r
        objectives = [r["objective"] for r in results.values() if r.get("objective") is not None]
        reference = min(objectives) if objectives else None
        for solver, r in results.items():
            ok = r["status"] == "optimal" and reference is not None and close(r["objective"], reference)
            tally.check(ok, f"stones8x4 {solver}", f"{describe(r)}; best of all peers {reference}")
            r = solve(args.python, solver, mps, 60, ["--split-ranges"])
            ok = r["status"] == "optimal" and reference is not None and close(r["objective"], reference)
            tally.check(ok, f"stones8x4 {solver} --split-ranges", describe(r))

        # 3. Licence-size refusals are reported as such.
        for steps, limited in ((30, ("gurobi",)), (130, ("cplex", "copt"))):
            mps = os.path.join(tmp, f"stones{steps}x6.mps")
            subprocess.run([sys.executable, os.path.join(HERE, "make_instances.py"), "stones", mps,
                            "--steps", str(steps), "--stones", "6"], check=True)
            for solver in limited:
                if solver not in solvers:
                    continue
                r = run(solver, mps, 2)
                if r["status"] == "unavailable":
                    continue
                ok = r["status"] in ("refused", "optimal", "feasible", "time_limit")
                tally.check(ok, f"stones{steps}x6 {solver} (size limit)", describe(r))

        # Gurobi counts a variable per ranged row: 162 columns + 40 ranged rows is over its
        # 200-variable limit, the same problem with the ranges split is not.
        if "gurobi" in solvers:
            mps = os.path.join(tmp, "stones20x6.mps")
            subprocess.run([sys.executable, os.path.join(HERE, "make_instances.py"), "stones", mps,
                            "--steps", "20", "--stones", "6"], check=True)
            whole = run("gurobi", mps, 10)
            if whole["status"] != "unavailable":
                tally.check(whole["status"] in ("refused", "optimal", "feasible", "time_limit"),
                            "stones20x6 gurobi (162 columns, 40 ranged rows)", describe(whole))
                split = solve(args.python, "gurobi", mps, 10, ["--split-ranges"])
                tally.check(split["status"] in ("optimal", "feasible", "time_limit"),
                            "stones20x6 gurobi --split-ranges", describe(split))

    if tally.skipped:
        print("skipped (not installed): " + "; ".join(sorted(tally.skipped)))
    print(f"{tally.passed} passed, {tally.failed} failed")
    return 1 if tally.failed else 0


if __name__ == "__main__":
    sys.exit(main())
