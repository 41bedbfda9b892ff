#!/usr/bin/env python3
"""Runs the peer MIQP solvers on mfp's MPS exports and tables them against mfp.

    run_peers.py --instances DIR [--solvers scip,copt,cplex,gurobi,bonmin]
                 [--time-limit 60] [--mip-gap G] [--split-ranges gurobi]
                 [--out FILE.md] [--out FILE.json] [--strict]

DIR holds pairs NAME.mps + NAME.json. NAME.json is mfp's plan JSON (DESIGN.md) for the
same instance, as written by `mfp-plan --window N --max-steps N --write-mps NAME.mps
--json NAME.json`; the fields used are objective_offset (objective = MPS objective +
objective_offset), objective, bound, solve_time_s, status and nodes. A NAME.json without
mfp's fields (a generated or hand-made instance) still gives the peers' rows; a missing
NAME.json means an offset of 0, said so in the notes.

Each peer runs in its own process, one after the other, with one thread and the time
limit; a process that overruns the limit by far is killed and shown as such. A peer
that refuses an instance (licence size) is shown as "refused", never left out.

Per instance and peer: time, objective and bound (both plus the offset, so they compare
with mfp's objective), status, mfp's time over the peer's time, and (SCIP, which lists
its solutions with their times) when the peer first held a solution within 0.5 % of the
best objective any solver found: the time to compare with mfp-bench's within_s. Per instance: the
best objective any peer found, mfp's gap to it, the best proven bound and mfp's gap to
that, and warnings when peers that claim optimality disagree or when mfp's objective is
below a peer's proven bound (which would mean the export and mfp's model differ).
"""

import argparse
import glob
import json
import math
import os
import subprocess
import sys

from solve_mps import mps_records

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
VENV_PYTHON = os.path.join(REPO, "bench", ".venv", "bin", "python")
ALL_SOLVERS = ("gurobi", "cplex", "copt", "scip", "bonmin")
# "Within" for the time to a good solution: the targets count a plan within 0.5 %
# of the best objective any solver found.
WITHIN = 0.005
# Two objectives agree when they differ by at most this (absolute + relative).
ABS_TOL = 1e-4
REL_TOL = 1e-4


def mps_size(path):
    """(columns, integer columns, rows other than the objective) of a free MPS file."""
    rows = 0
    columns = set()
    integers = set()
    in_int = False
    with open(path) as f:
        for section, fields in mps_records(f):
            if section == "ROWS":
                rows += fields[0].upper() != "N"
            elif section == "COLUMNS":
                if len(fields) >= 3 and fields[1].strip("'\"").upper() == "MARKER":
                    in_int = fields[2].strip("'\"").upper() == "INTORG"
                    continue
                columns.add(fields[0])
                if in_int:
                    integers.add(fields[0])
            elif section == "BOUNDS" and fields[0].upper() in ("BV", "LI", "UI"):
                integers.add(fields[2])
    return len(columns), len(integers), rows


def agree(a, b):
    return abs(a - b) <= ABS_TOL + REL_TOL * max(abs(a), abs(b))


def add(value, offset):
    return None if value is None else value + offset


def relative_gap(value, reference):
    """(value - reference) / max(|reference|, 1e-9)."""
    if value is None or reference is None:
        return None
    return (value - reference) / max(abs(reference), 1e-9)


def run_peer(solver, mps, args):
    python = args.python
    cmd = [python, os.path.join(HERE, "solve_mps.py"), "--solver", solver, mps,
           "--time-limit", str(args.time_limit), "--threads", "1"]
    if args.mip_gap is not None:
        cmd += ["--mip-gap", str(args.mip_gap)]
    if args.bonmin_driver:
        cmd += ["--bonmin-driver", args.bonmin_driver]
    if solver in args.split_ranges:
        cmd.append("--split-ranges")
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    hard_limit = args.time_limit * 1.5 + 30
    try:
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=None if args.verbose else subprocess.DEVNULL,
                              text=True, timeout=hard_limit, env=env, check=False)
    except subprocess.TimeoutExpired:
        return {"solver": solver, "status": "time_limit", "time_s": hard_limit, "objective": None,
                "bound": None, "version": "",
                "message": f"killed: still running {hard_limit:.0f} s after start (time limit {args.time_limit} s)"}
    lines = [ln for ln in proc.stdout.splitlines() if ln.startswith("{")]
    if not lines:
        return {"solver": solver, "status": "error", "time_s": None, "objective": None, "bound": None,
                "version": "", "message": f"solve_mps.py exited {proc.returncode} without a result"}
    return json.loads(lines[-1])


def load_plan(json_path):
    if not os.path.exists(json_path):
        return {}, [f"{os.path.basename(json_path)} missing: objective offset taken as 0, no mfp result"]
    with open(json_path) as f:
        plan = json.load(f)
    notes = []
    if "objective_offset" not in plan:
        notes.append("plan JSON has no objective_offset: taken as 0")
    return plan, notes


def evaluate(name, mps, args):
    plan, notes = load_plan(mps[:-4] + ".json")
    offset = float(plan.get("objective_offset", 0.0))
    columns, integers, rows = mps_size(mps)
    mfp = None
    if "objective" in plan and "solve_time_s" in plan:
        mfp = {"status": plan.get("status"), "time_s": plan.get("solve_time_s"),
               "objective": plan.get("objective"), "bound": plan.get("bound"),
               "nodes": plan.get("nodes")}
    peers = []
    for solver in args.solvers:
        r = run_peer(solver, mps, args)
        r["objective_with_offset"] = add(r.get("objective"), offset)
        r["bound_with_offset"] = add(r.get("bound"), offset)
        usable = r["status"] in ("optimal", "feasible", "time_limit") and r.get("time_s")
        r["mfp_time_ratio"] = (mfp["time_s"] / r["time_s"]) if (mfp and mfp["time_s"] is not None and usable) else None
        peers.append(r)
        print(f"  {name}: {solver:7s} {r['status']:11s} {fmt(r.get('time_s'), 's')}", file=sys.stderr, flush=True)

    found = [p["objective_with_offset"] for p in peers if p["objective_with_offset"] is not None]
    best = min(found) if found else None
    best_solver = next((p["solver"] for p in peers if p["objective_with_offset"] == best), None) if found else None
    bounds = [p["bound_with_offset"] for p in peers
              if p["bound_with_offset"] is not None and p["status"] in ("optimal", "feasible", "time_limit")]
    best_bound = max(bounds) if bounds else None
    optimal = [p for p in peers if p["status"] == "optimal" and p["objective_with_offset"] is not None]
    for p in optimal:
        for q in optimal:
            if p["solver"] < q["solver"] and not agree(p["objective_with_offset"], q["objective_with_offset"]):
                notes.append(f"DISAGREE: {p['solver']} and {q['solver']} both claim optimality with "
                             f"{p['objective_with_offset']:.6g} vs {q['objective_with_offset']:.6g}")
    infeasible = [p["solver"] for p in peers if p["status"] == "infeasible"]
    if infeasible and found:
        notes.append(f"DISAGREE: {', '.join(infeasible)} report infeasible, others found a solution")
    best_any = min([v for v in found + [mfp and mfp["objective"]] if v is not None], default=None)
    for p in peers:
        p["within_s"] = first_within(p.get("solutions") or [], offset, best_any)
    summary = {"best_objective": best, "best_solver": best_solver, "best_bound": best_bound}
    if mfp and mfp["objective"] is not None:
        summary["mfp_gap_to_best"] = relative_gap(mfp["objective"], best)
        summary["mfp_abs_gap_to_best"] = None if best is None else mfp["objective"] - best
        summary["mfp_gap_to_best_bound"] = relative_gap(mfp["objective"], best_bound)
        if best_bound is not None and mfp["objective"] < best_bound and not agree(mfp["objective"], best_bound):
            notes.append(f"CHECK EXPORT: mfp's objective {mfp['objective']:.6g} is below the peers' proven "
                         f"bound {best_bound:.6g}: the MPS and mfp's model may differ")
    return {"instance": name, "mps": mps, "columns": columns, "integer_variables": integers, "rows": rows,
            "objective_offset": offset, "mfp": mfp, "peers": peers, "summary": summary, "notes": notes}


def first_within(solutions, offset, best):
    """The earliest time of a solution within WITHIN of best (objectives plus offset)."""
    if best is None:
        return None
    limit = best + WITHIN * max(1.0, abs(best))
    times = [t for t, objective in solutions if objective + offset <= limit]
    return min(times) if times else None


def fmt(value, unit="", digits=4):
    if value is None:
        return "-"
    if isinstance(value, float) and (math.isinf(value) or math.isnan(value)):
        return "-"
    if unit == "s":
        return f"{value:.3g} s" if value < 100 else f"{value:.0f} s"
    if unit == "%":
        return f"{100 * value:.3g}%"
    if unit == "x":
        return f"{value:.3g}x"
    return f"{value:.{digits + 3}g}"


HEADER = ["instance", "int vars", "cols", "rows", "solver", "status", "time", "objective", "bound",
          "mfp time / solver time", "first within 0.5 %"]


def table_rows(results):
    rows = []
    for res in results:
        lead = [res["instance"], str(res["integer_variables"]), str(res["columns"]), str(res["rows"])]
        if res["mfp"]:
            m = res["mfp"]
            rows.append(lead + ["mfp", str(m["status"]), fmt(m["time_s"], "s"), fmt(m["objective"]),
                                fmt(m["bound"]), "", "mfp-bench within_s"])
            lead = ["", "", "", ""]
        for p in res["peers"]:
            status = p["status"]
            if status in ("refused", "unavailable", "error"):
                status += f" ({p['message']})" if p.get("message") else ""
            ratio = fmt(p["mfp_time_ratio"], "x")
            if p["mfp_time_ratio"] is not None and p["status"] == "time_limit":
                ratio = "<= " + ratio  # the peer stopped at its limit
            within = fmt(p["within_s"], "s") if p.get("solutions") else "-"
            rows.append(lead + [p["solver"], status, fmt(p.get("time_s"), "s"),
                                fmt(p["objective_with_offset"]), fmt(p["bound_with_offset"]), ratio, within])
            lead = ["", "", "", ""]
    return rows


SUMMARY_HEADER = ["instance", "best peer objective", "by", "best peer bound", "mfp objective",
                  "mfp gap to best objective", "mfp gap to best bound", "notes"]


def summary_rows(results):
    rows = []
    for res in results:
        s = res["summary"]
        m = res["mfp"] or {}
        rows.append([res["instance"], fmt(s["best_objective"]), s["best_solver"] or "-", fmt(s["best_bound"]),
                     fmt(m.get("objective")), fmt(s.get("mfp_gap_to_best"), "%"),
                     fmt(s.get("mfp_gap_to_best_bound"), "%"), "; ".join(res["notes"])])
    return rows


def text_table(header, rows):
    widths = [max(len(str(r[i])) for r in [header] + rows) for i in range(len(header))]
    widths = [min(w, 60) for w in widths]
    line = lambda r: "  ".join(str(c)[:60].ljust(w) for c, w in zip(r, widths)).rstrip()
    return "\n".join([line(header), line(["-" * w for w in widths])] + [line(r) for r in rows])


def markdown_table(header, rows):
    esc = lambda c: str(c).replace("|", "\\|")
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(esc(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def versions(results):
    seen = {}
    for res in results:
        for p in res["peers"]:
            if p.get("version"):
                seen[p["solver"]] = p["version"]
    return seen


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--instances", required=True, metavar="DIR", help="directory of NAME.mps + NAME.json")
    parser.add_argument("--solvers", default=",".join(ALL_SOLVERS),
                        help=f"comma-separated subset of {','.join(ALL_SOLVERS)} (default: all)")
    parser.add_argument("--time-limit", type=float, default=60.0, help="seconds per peer and instance (default 60)")
    parser.add_argument("--mip-gap", type=float, default=None, help="relative gap passed to every peer")
    parser.add_argument("--out", action="append", default=[],
                        help="write the results to FILE.md or FILE.json (may be repeated)")
    parser.add_argument("--python", default=VENV_PYTHON if os.path.exists(VENV_PYTHON) else sys.executable,
                        help="interpreter with the solver packages (default: bench/.venv)")
    parser.add_argument("--bonmin-driver", default=None, help="path of bonmin_mps (default: build-peers/)")
    parser.add_argument("--split-ranges", default="", metavar="SOLVERS",
                        help="comma-separated peers given a copy of each file with every ranged row "
                             "as two rows; e.g. 'gurobi', whose licence counts a variable per ranged row "
                             "(default: none, every peer reads the identical file)")
    parser.add_argument("--strict", action="store_true",
                        help="exit 1 when peers disagree or mfp's objective is below a proven bound")
    parser.add_argument("--verbose", action="store_true", help="solver logs on stderr")
    args = parser.parse_args()
    args.solvers = [s.strip() for s in args.solvers.split(",") if s.strip()]
    args.split_ranges = [s.strip() for s in args.split_ranges.split(",") if s.strip()]
    bad = [s for s in args.solvers + args.split_ranges if s not in ALL_SOLVERS]
    if bad:
        parser.error(f"unknown solver(s) {bad}; allowed: {', '.join(ALL_SOLVERS)}")
    if args.time_limit <= 0:
        parser.error("--time-limit must be > 0")
    for out in args.out:
        if not out.endswith((".md", ".json")):
            parser.error(f"--out {out}: must end in .md or .json")
    files = sorted(glob.glob(os.path.join(args.instances, "*.mps")))
    if not files:
        parser.error(f"no .mps files in {args.instances}")

    results = []
    for mps in files:
        name = os.path.basename(mps)[:-4]
        results.append(evaluate(name, os.path.abspath(mps), args))

    header_note = (f"Peers: one thread each, time limit {args.time_limit:g} s"
                   + (f", relative MIP gap {args.mip_gap:g}" if args.mip_gap is not None else ", each solver's default MIP gap")
                   + ". Objectives and bounds include the plan JSON's objective_offset."
                   + (f" Ranged rows split into two rows for: {', '.join(args.split_ranges)}."
                      if args.split_ranges else "")
                   + " Versions: " + ", ".join(f"{k} = {v}" for k, v in versions(results).items()) + ".")
    print(header_note)
    print()
    print(text_table(HEADER, table_rows(results)))
    print()
    print(text_table(SUMMARY_HEADER, summary_rows(results)))
    for out in args.out:
        with open(out, "w") as f:
            if out.endswith(".json"):
                json.dump({"time_limit_s": args.time_limit, "mip_gap": args.mip_gap,
                           "versions": versions(results), "instances": results}, f, indent=1)
                f.write("\n")
            else:
                f.write("# mfp against peer MIQP solvers\n\n" + header_note + "\n\n")
                f.write(markdown_table(HEADER, table_rows(results)) + "\n\n")
                f.write(markdown_table(SUMMARY_HEADER, summary_rows(results)) + "\n")
    disagreements = any(n.startswith(("DISAGREE", "CHECK EXPORT")) for r in results for n in r["notes"])
    return 1 if disagreements and args.strict else 0


if __name__ == "__main__":
    sys.exit(main())
