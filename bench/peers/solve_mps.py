#!/usr/bin/env python3
"""Solve one MPS file (free MPS, QUADOBJ) with one peer MIQP solver; print one JSON line.

    solve_mps.py --solver scip|copt|cplex|gurobi|bonmin FILE.mps --time-limit S [--threads 1]

Printed fields: solver, version, status (optimal|feasible|time_limit|infeasible|refused|
error|unavailable), time_s (wall time of the solve call, reading excluded), objective and
bound (as the solver reports them: the constant term mfp keeps in its plan JSON is NOT
added here), message, and for SCIP solutions: [time_s, objective] of each solution it
kept (SCIP's solving clock), from which run_peers.py reads when a solution within 0.5 %
of the best first appeared. The solver's own log goes to stderr with --verbose, else nowhere,
so that stdout carries only the JSON line.

Licence-size refusals (CPLEX Community Edition, the size-limited Gurobi and COPT
licences) are reported as status "refused" with the solver's own words in message.
A solver whose Python package is not installed is "unavailable", never a crash.
"""

import argparse
import contextlib
import importlib
import importlib.metadata
import json
import os
import subprocess
import sys
import tempfile
import time

SOLVERS = ("scip", "copt", "cplex", "gurobi", "bonmin")
HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_BONMIN_DRIVER = os.path.join(HERE, "..", "..", "build-peers", "bonmin_mps")


def finite_or_none(value):
    """A float for JSON, or None for a missing / infinite value."""
    if value is None:
        return None
    value = float(value)
    if value != value or abs(value) >= 1e20:
        return None
    return value


@contextlib.contextmanager
def solver_output_to(verbose):
    """Send whatever the solver libraries print on fd 1 and fd 2 away from stdout.

    Solvers print banners from C code, so sys.stdout redirection is not enough: the file
    descriptors themselves are redirected, to stderr with --verbose, else to /dev/null.
    """
    sys.stdout.flush()
    sys.stderr.flush()
    saved_out = os.dup(1)
    saved_err = os.dup(2)
    target = os.dup(2) if verbose else os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(target, 1)
        if not verbose:
            os.dup2(target, 2)
        yield
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os.dup2(saved_out, 1)
        os.dup2(saved_err, 2)
        for fd in (saved_out, saved_err, target):
            os.close(fd)


def package_version(name):
    try:
        return importlib.metadata.version(name)
    except importlib.metadata.PackageNotFoundError:
        return "?"


def result(solver, status, time_s=None, objective=None, bound=None, message="", version="", solutions=None):
    if status in ("infeasible", "refused", "unavailable"):
        bound = None  # CPLEX reports a meaningless 0 as the bound of an infeasible MIP
    return {
        "solver": solver,
        "version": version,
        "status": status,
        "time_s": time_s,
        "objective": finite_or_none(objective),
        "bound": finite_or_none(bound),
        "message": message,
        "solutions": solutions or [],
    }


def mps_records(lines):
    """(section, fields) for each data line of a free MPS file: comments, blank lines and
    the section header lines themselves are skipped; section is the upper-case name of
    the section the line belongs to."""
    section = None
    for line in lines:
        if not line.strip() or line.startswith("*"):
            continue
        if not line[0].isspace():
            section = line.split()[0].upper()
            continue
        yield section, line.split()


def split_ranged_rows(path, out_path):
    """Writes to out_path the same problem with each ranged row as two rows (L and G).

    Gurobi turns every ranged row into an equality plus a variable of its own, and those
    variables count against its size-limited licence (200 variables with a quadratic
    objective). The copy is the same feasible set and objective without ranges; the
    row that keeps the original name holds the upper side, ROW__lo the lower side.
    Returns the number of rows split.
    """
    with open(path) as f:
        lines = f.read().splitlines()
    rhs_set = None  # the name of the RHS vector, so that the added entries join it
    sense, rhs, rng = {}, {}, {}
    for section, fields in mps_records(lines):
        if section == "ROWS":
            sense[fields[1]] = fields[0].upper()
        elif section in ("RHS", "RANGES"):
            target = rhs if section == "RHS" else rng
            if section == "RHS" and len(fields) % 2 == 1 and rhs_set is None:
                rhs_set = fields[0]
            pairs = fields[1:] if len(fields) % 2 == 1 else fields
            for name, value in zip(pairs[0::2], pairs[1::2]):
                target[name] = float(value)
    bounds = {}
    for row, r in rng.items():
        b = rhs.get(row, 0.0)
        kind = sense[row]
        if kind == "N":
            continue
        if kind == "L":
            lo, hi = b - abs(r), b
        elif kind == "G":
            lo, hi = b, b + abs(r)
        else:
            lo, hi = (b, b + r) if r >= 0 else (b + r, b)
        bounds[row] = (lo, hi)
    rhs_set = rhs_set or "RHS"
    split_rhs = [f" {rhs_set} {row} {hi!r}" for row, (lo, hi) in bounds.items()]
    split_rhs += [f" {rhs_set} {row}__lo {lo!r}" for row, (lo, hi) in bounds.items()]
    out = []
    section = None
    seen_rhs = False
    for line in lines:
        if line.strip() and not line.startswith("*") and not line[0].isspace():
            if section == "RHS":
                out += split_rhs
            section = line.split()[0].upper()
            if section == "RHS":
                seen_rhs = True
            elif section in ("RANGES", "BOUNDS", "QUADOBJ", "ENDATA") and not seen_rhs:
                out += ["RHS"] + split_rhs
                seen_rhs = True
            if section != "RANGES":
                out.append(line)
            continue
        if section == "RANGES":
            continue
        fields = line.split()
        if not fields or line.startswith("*"):
            out.append(line)
        elif section == "ROWS" and fields[1] in bounds:
            out += [f" L {fields[1]}", f" G {fields[1]}__lo"]
        elif section == "COLUMNS" and not (len(fields) >= 3 and "MARKER" in fields[1].upper()):
            col, pairs = fields[0], fields[1:]
            for name, value in zip(pairs[0::2], pairs[1::2]):
                out.append(f" {col} {name} {value}")
                if name in bounds:
                    out.append(f" {col} {name}__lo {value}")
        elif section == "RHS":
            pairs = fields[1:] if len(fields) % 2 == 1 else fields
            set_name = fields[0] if len(fields) % 2 == 1 else rhs_set
            for name, value in zip(pairs[0::2], pairs[1::2]):
                if name not in bounds:
                    out.append(f" {set_name} {name} {value}")
        else:
            out.append(line)
    with open(out_path, "w") as f:
        f.write("\n".join(out) + "\n")
    return len(bounds)


def import_peer(solver, module):
    """The peer's Python module and None, or None and an "unavailable" result saying why."""
    try:
        return importlib.import_module(module), None
    except ImportError as e:
        return None, result(solver, "unavailable", message=f"{module} not importable: {e}")


# --------------------------------------------------------------------------- SCIP

def solve_scip(path, time_limit, threads, mip_gap):
    pyscipopt, unavailable = import_peer("scip", "pyscipopt")
    if unavailable:
        return unavailable
    model = pyscipopt.Model()
    version = f"SCIP {model.version()} (pyscipopt {pyscipopt.__version__})"
    model.hideOutput()
    model.readProblem(path)
    model.setParam("limits/time", time_limit)
    model.setParam("lp/threads", threads)
    model.setParam("parallel/maxnthreads", threads)
    if mip_gap is not None:
        model.setParam("limits/gap", mip_gap)
    start = time.perf_counter()
    model.optimize()
    elapsed = time.perf_counter() - start
    scip_status = model.getStatus()
    has_solution = model.getNSols() > 0
    objective = model.getObjVal() if has_solution else None
    bound = model.getDualbound()
    if scip_status == "optimal":
        status = "optimal"
    elif scip_status == "infeasible":
        status = "infeasible"
    elif scip_status in ("timelimit", "gaplimit") and has_solution:
        status = "time_limit" if scip_status == "timelimit" else "feasible"
    elif scip_status == "timelimit":
        status = "time_limit"
    else:
        status = "feasible" if has_solution else "error"
    solutions = sorted([model.getSolTime(sol), model.getSolObjVal(sol)] for sol in model.getSols())
    return result("scip", status, elapsed, objective, bound, f"SCIP status {scip_status}", version, solutions)


# --------------------------------------------------------------------------- COPT

COPT_SIZE_WORDS = ("size", "limit", "licen")


def solve_copt(path, time_limit, threads, mip_gap):
    coptpy, unavailable = import_peer("copt", "coptpy")
    if unavailable:
        return unavailable
    COPT = coptpy.COPT
    version = f"COPT {package_version('coptpy')}"
    env = coptpy.Envr()

    solve_seconds = [0.0]  # over all attempts; reading the file is not counted

    def attempt(extra_params):
        model = env.createModel("peer")
        model.setParam(COPT.Param.Logging, 1)
        model.read(path)
        model.setParam(COPT.Param.TimeLimit, max(time_limit - solve_seconds[0], 0.01))
        model.setParam(COPT.Param.Threads, threads)
        if mip_gap is not None:
            model.setParam(COPT.Param.RelGap, mip_gap)
        for name, value in extra_params.items():
            model.setParam(name, value)
        start = time.perf_counter()
        try:
            model.solve()
        finally:
            solve_seconds[0] += time.perf_counter() - start
        return model

    notes = []
    try:
        try:
            model = attempt({})
        except coptpy.CoptError as e:
            text = str(e)
            if "(INTERNAL)" not in text:
                raise  # a read error or a licence refusal: retrying would not help
            # COPT 8's presolve turns some small convex MIQPs into conic form and then
            # fails ("Fail to solve problem"); the same model solves with presolve off.
            # The time of the failed attempt is kept in time_s, and the retry gets what is
            # left of the time limit.
            notes.append(f"default settings failed ({text}); retried with Presolve=0")
            model = attempt({"Presolve": 0})
    except coptpy.CoptError as e:
        elapsed = solve_seconds[0] or None  # None: failed before solving (reading)
        text = "; ".join(notes + [str(e)])
        status = "refused" if any(w in str(e).lower() for w in ("size", "licen")) else "error"
        if status == "refused":
            # COPT's exception says only "(LICENSE) Fail to solve problem"; its log says why.
            text += " (no licence file: COPT is limited to 2000 variables and 2000 constraints)"
        return result("copt", status, elapsed, message=text, version=version)
    elapsed = solve_seconds[0]
    code = model.status
    is_mip = model.getAttr("IsMIP")
    has_solution = model.getAttr("HasMipSol") if is_mip else code == COPT.OPTIMAL
    objective = (model.getAttr("BestObj") if is_mip else model.objval) if has_solution else None
    bound = model.getAttr("BestBnd") if is_mip else (model.objval if code == COPT.OPTIMAL else None)
    names = {COPT.OPTIMAL: "optimal", COPT.INFEASIBLE: "infeasible", COPT.TIMEOUT: "time_limit",
             COPT.NODELIMIT: "feasible", COPT.UNBOUNDED: "error", COPT.INF_OR_UNB: "infeasible",
             COPT.NUMERICAL: "error", COPT.INTERRUPTED: "error", COPT.UNFINISHED: "error"}
    status = names.get(code, "error")
    if status == "error" and has_solution:
        status = "feasible"
    notes.append(f"COPT status {code}")
    return result("copt", status, elapsed, objective, bound, "; ".join(notes), version)


# --------------------------------------------------------------------------- CPLEX

CPXERR_RESTRICTED_VERSION = 1016


def solve_cplex(path, time_limit, threads, mip_gap):
    cplex, unavailable = import_peer("cplex", "cplex")
    if unavailable:
        return unavailable
    from cplex.exceptions import CplexSolverError
    cpx = cplex.Cplex()
    version = f"CPLEX {cpx.get_version()}"
    cpx.read(path)
    cpx.parameters.threads.set(threads)
    cpx.parameters.timelimit.set(time_limit)
    if mip_gap is not None:
        cpx.parameters.mip.tolerances.mipgap.set(mip_gap)
    start = time.perf_counter()
    try:
        cpx.solve()
    except CplexSolverError as e:
        elapsed = time.perf_counter() - start
        status = "refused" if e.args[2] == CPXERR_RESTRICTED_VERSION else "error"
        return result("cplex", status, elapsed, message=str(e).strip(), version=version)
    elapsed = time.perf_counter() - start
    sol = cpx.solution
    code = sol.get_status()
    text = sol.get_status_string()
    is_mip = cpx.problem_type[cpx.get_problem_type()] not in ("LP", "QP", "QCP")
    has_solution = sol.is_primal_feasible()
    objective = sol.get_objective_value() if has_solution else None
    if is_mip:
        try:
            bound = sol.MIP.get_best_objective()
        except CplexSolverError:
            bound = None
    else:
        bound = objective if code == sol.status.optimal else None
    st = sol.status
    if code in (st.MIP_optimal, st.optimal_tolerance, st.optimal, getattr(st, "MIP_optimal_tolerance", -1)):
        status = "optimal"
    elif code in (st.MIP_infeasible, st.infeasible, st.MIP_infeasible_or_unbounded,
                  st.infeasible_or_unbounded):
        status = "infeasible"
    elif code in (st.MIP_time_limit_feasible, st.MIP_time_limit_infeasible, st.abort_time_limit):
        status = "time_limit"
    else:
        status = "feasible" if has_solution else "error"
    return result("cplex", status, elapsed, objective, bound, f"CPLEX status {code} ({text})", version)


# --------------------------------------------------------------------------- Gurobi

GRB_ERROR_SIZE_LIMIT_EXCEEDED = 10010


def solve_gurobi(path, time_limit, threads, mip_gap):
    gp, unavailable = import_peer("gurobi", "gurobipy")
    if unavailable:
        return unavailable
    GRB = gp.GRB
    version = "Gurobi {}.{}.{}".format(*gp.gurobi.version())
    env = gp.Env(empty=True)
    env.setParam("OutputFlag", 1)
    env.start()
    model = gp.read(path, env)
    model.Params.Threads = threads
    model.Params.TimeLimit = time_limit
    if mip_gap is not None:
        model.Params.MIPGap = mip_gap
    start = time.perf_counter()
    try:
        model.optimize()
    except gp.GurobiError as e:
        elapsed = time.perf_counter() - start
        status = "refused" if e.errno == GRB_ERROR_SIZE_LIMIT_EXCEEDED else "error"
        return result("gurobi", status, elapsed, message=f"Gurobi error {e.errno}: {e}", version=version)
    elapsed = time.perf_counter() - start
    code = model.Status
    has_solution = model.SolCount > 0
    objective = model.ObjVal if has_solution else None
    try:
        bound = model.ObjBound if model.IsMIP else (model.ObjVal if code == GRB.OPTIMAL else None)
    except gp.GurobiError:
        bound = None
    names = {GRB.OPTIMAL: "optimal", GRB.INFEASIBLE: "infeasible", GRB.INF_OR_UNBD: "infeasible",
             GRB.TIME_LIMIT: "time_limit", GRB.SUBOPTIMAL: "feasible"}
    status = names.get(code, "feasible" if has_solution else "error")
    return result("gurobi", status, elapsed, objective, bound, f"Gurobi status {code}", version)


# --------------------------------------------------------------------------- Bonmin

def solve_bonmin(path, time_limit, threads, mip_gap, driver, verbose):
    """Runs the C++ driver (bonmin_mps.cc), which prints the same JSON line."""
    if not os.path.exists(driver):
        return result("bonmin", "unavailable",
                      message=f"driver {driver} not built (run bench/peers/build_bonmin_driver.sh)")
    cmd = [driver, path, "--time-limit", str(time_limit)]
    if mip_gap is not None:
        cmd += ["--mip-gap", str(mip_gap)]
    if verbose:
        cmd.append("--verbose")
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=None if verbose else subprocess.DEVNULL,
                          text=True, check=False)
    lines = [ln for ln in proc.stdout.splitlines() if ln.startswith("{")]
    if not lines:
        return result("bonmin", "error", message=f"driver exited {proc.returncode} without a result")
    return json.loads(lines[-1])


def solve(solver, path, time_limit, threads, mip_gap, verbose, bonmin_driver, split_ranges=False):
    if split_ranges:
        with tempfile.TemporaryDirectory(prefix="solve_mps_") as tmp:
            copy = os.path.join(tmp, os.path.basename(path))
            count = split_ranged_rows(path, copy)
            out = solve(solver, copy, time_limit, threads, mip_gap, verbose, bonmin_driver)
        note = f"{count} ranged rows given as two rows each (--split-ranges)"
        out["message"] = note + ("; " + out["message"] if out.get("message") else "")
        return out
    if solver == "bonmin":
        return solve_bonmin(path, time_limit, threads, mip_gap, bonmin_driver, verbose)
    function = {"scip": solve_scip, "copt": solve_copt, "cplex": solve_cplex,
                "gurobi": solve_gurobi}[solver]
    with solver_output_to(verbose):
        try:
            return function(path, time_limit, threads, mip_gap)
        except Exception as e:  # a reader or solver failure is a result, not a crash
            package = {"scip": "pyscipopt", "copt": "coptpy", "cplex": "cplex", "gurobi": "gurobipy"}[solver]
            return result(solver, "error", message=f"{type(e).__name__}: {e}",
                          version=f"{package} {package_version(package)}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mps", metavar="FILE.mps")
    parser.add_argument("--solver", required=True, choices=SOLVERS)
    parser.add_argument("--time-limit", type=float, default=60.0, help="seconds (default 60)")
    parser.add_argument("--threads", type=int, default=1, help="solver threads (default 1)")
    parser.add_argument("--mip-gap", type=float, default=None,
                        help="relative MIP gap to stop at (default: each solver's own)")
    parser.add_argument("--bonmin-driver", default=os.environ.get("MFP_BONMIN_DRIVER", DEFAULT_BONMIN_DRIVER),
                        help="path of the built bonmin_mps driver")
    parser.add_argument("--split-ranges", action="store_true",
                        help="give the solver a copy with each ranged row as two rows (L and G)")
    parser.add_argument("--verbose", action="store_true", help="solver logs on stderr")
    args = parser.parse_args(argv)
    if not os.path.isfile(args.mps):
        parser.error(f"{args.mps}: no such file")
    if args.time_limit <= 0:
        parser.error("--time-limit must be > 0 seconds")
    if args.threads < 1:
        parser.error("--threads must be >= 1")
    # One thread also for the BLAS / OpenMP below the solvers (Ipopt's MUMPS in Bonmin).
    for name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[name] = str(args.threads)
    out = solve(args.solver, os.path.abspath(args.mps), args.time_limit, args.threads, args.mip_gap,
                args.verbose, os.path.abspath(args.bonmin_driver), args.split_ranges)
    print(json.dumps(out), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
