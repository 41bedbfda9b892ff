#!/usr/bin/env python3
"""How SCIP searches one MPS file: nodes, depth, what it branches on, and its bound curve.

    scip_search_stats.py FILE.mps [--time-limit 120] [--stats OUT.txt] [--trace OUT.csv]
                         [--write-sol OUT.sol] [--set name=value ...]

Prints one JSON line: status, time, nodes, max depth, objective, dual bound, the root's
dual bound, the branchings per variable family (the name's prefix before the first
'[' or '_'), and the bound trace as [nodes, dual bound, primal bound] every time the dual
bound rises by 0.5 % of the gap at the root (also written to --trace as CSV). The full
`writeStatistics` text goes to --stats. One thread; SCIP's output nowhere.
"""

import argparse
import collections
import json
import re

import pyscipopt
from pyscipopt import SCIP_EVENTTYPE, SCIP_PARAMSETTING  # noqa: F401


def family(name):
    """The variable family: the name up to its first index ('t_H_3_2' -> 'H'; SCIP names
    its transformed variables 't_' + the original name)."""
    if name.startswith("t_"):
        name = name[2:]
    return re.split(r"[\[_(.0-9]", name, maxsplit=1)[0] or name


class BoundTrace(pyscipopt.Eventhdlr):
    """Records (nodes, dual bound, primal bound) whenever the dual bound has risen, and
    counts branchings per variable family from each solved node's branching decision."""

    def __init__(self):
        super().__init__()
        self.trace = []
        self.last_bound = None
        self.branchings = collections.Counter()
        self.max_depth = 0

    def eventinit(self):
        self.model.catchEvent(SCIP_EVENTTYPE.NODESOLVED, self)

    def eventexit(self):
        self.model.dropEvent(SCIP_EVENTTYPE.NODESOLVED, self)

    def eventexec(self, event):
        m = self.model
        node = event.getNode()
        self.max_depth = max(self.max_depth, node.getDepth())
        if node.getDepth() > 0:
            bvars, _, _ = node.getParentBranchings()
            for v in bvars or []:
                self.branchings[family(v.name)] += 1
        bound = m.getDualbound()
        if self.last_bound is None or bound > self.last_bound + 1e-9 * (1 + abs(bound)):
            self.trace.append([m.getNNodes(), bound, m.getPrimalbound(), m.getSolvingTime()])
            self.last_bound = bound


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mps")
    ap.add_argument("--time-limit", type=float, default=120.0)
    ap.add_argument("--stats")
    ap.add_argument("--trace")
    ap.add_argument("--write-sol", help="write SCIP's best solution here (SCIP's .sol format)")
    ap.add_argument("--set", action="append", default=[], help="SCIP parameter name=value")
    a = ap.parse_args()
    m = pyscipopt.Model()
    m.hideOutput()
    m.readProblem(a.mps)
    m.setParam("limits/time", a.time_limit)
    m.setParam("lp/threads", 1)
    m.setParam("parallel/maxnthreads", 1)
    for kv in a.set:
        k, v = kv.split("=", 1)
        try:
            m.setParam(k, float(v) if "." in v or "e" in v else int(v))
        except (TypeError, ValueError, LookupError):
            m.setParam(k, v)
    tracer = BoundTrace()
    m.includeEventhdlr(tracer, "boundtrace", "dual bound trace")
    m.optimize()
    out = {
        "status": m.getStatus(),
        "time_s": m.getSolvingTime(),
        "nodes": m.getNNodes(),
        "max_depth": tracer.max_depth,
        "objective": m.getObjVal() if m.getNSols() else None,
        "dual_bound": m.getDualbound(),
        "root_dual_bound": m.getDualboundRoot(),
        "branchings_by_family": dict(tracer.branchings.most_common()),
    }
    root = out["root_dual_bound"]
    best = out["objective"]
    thinned = []
    for row in tracer.trace:
        if best is not None and thinned and row[1] - thinned[-1][1] < 0.005 * (best - root):
            continue
        thinned.append(row)
    if tracer.trace and (not thinned or thinned[-1] is not tracer.trace[-1]):
        thinned.append(tracer.trace[-1])
    out["trace"] = thinned
    print(json.dumps(out))
    if a.trace:
        with open(a.trace, "w") as f:
            f.write("nodes,dual_bound,primal_bound,time_s\n")
            for row in tracer.trace:
                f.write(",".join(str(v) for v in row) + "\n")
    if a.stats:
        m.writeStatistics(a.stats)
    if a.write_sol and m.getNSols():
        m.writeBestSol(a.write_sol)


if __name__ == "__main__":
    main()
