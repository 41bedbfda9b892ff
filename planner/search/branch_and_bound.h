#pragma once
// Branch-and-bound for Miqp over a RelaxationSolver, with rounding heuristics. Anytime:
// it keeps the incumbent, the best bound and the gap, and on a node or time limit
// returns the best feasible point found.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "base/deadline.h"
#include "base/solve_status.h"
#include "planner/miqp/miqp.h"
#include "planner/qp/relaxation_solver.h"

namespace mfp {

enum class NodeSelection {
  kBestBound,             // smallest parent bound first
  kDepthFirst,            // newest node first
  kDiveThenBestBound,     // depth first until an incumbent exists, then best bound
  kBestBoundWithPlunging,  // best bound, but after branching go on into the preferred child
                           // while its bound lies within plunge_fraction of the way from the
                           // best bound to the incumbent (always, before an incumbent exists)
};

enum class BranchingRule {
  kMostFractional,  // the integer variable closest to 0.5
  kSos1Split,       // the most fractional member of any one-of group; its up-branch fixes the group
  kGroupOrder,      // the first one-of group (in the order the model lists them: along the
                    // plan) with a fractional member; then as kSos1Split within it
  kReliability,     // pseudo-costs, learnt from every child; candidates whose pseudo-costs
                    // are not yet reliable are strong-branched (both children solved)
};

struct BranchAndBoundResult;

// The bounds one variable is kept within (BranchAndBoundOptions::recertify_within).
struct VariableRange {
  int index = -1;
  double lower = -kInfinity, upper = kInfinity;
};

// The cut families of the root cut loop (BranchAndBoundOptions::root_cut_families).
enum RootCutFamily : int {
  kMirCuts = 1,            // c-MIR on aggregated rows (mir_cuts.h)
  kGroupBoundCuts = 2,     // a variable's bounds over a one-of group (mir_cuts.h)
  kImpliedBoundCuts = 4,   // bounds implied by probing a binary (implied_cuts.h)
  kCliqueCuts = 8,         // cliques of the probing's conflict graph (implied_cuts.h)
};
constexpr int kAllRootCutFamilies = kMirCuts | kGroupBoundCuts | kImpliedBoundCuts | kCliqueCuts;

// The levers BranchAndBoundOptions::long_search_only may keep to long searches.
enum LongSearchLever : int {
  kLongSearchProbing = 1,   // group_probing: a node (or the root) is probed only while the search is long
  kLongSearchRins = 2,      // rins_frequency: a RINS run is started only while the search is long
  kLongSearchRootCuts = 4,  // root_cut_rounds: the search runs without cuts until it is long, then the
                            // cut loop runs at its root and the search starts again with the cuts
};
constexpr int kAllLongSearchLevers = kLongSearchProbing | kLongSearchRins | kLongSearchRootCuts;

struct BranchAndBoundOptions {
  double time_limit_s = 10.0;
  // The caller's deadline (a whole plan's limit, a stop flag): the search ends at the
  // sooner of it and time_limit_s from its start, checked between nodes and inside
  // every relaxation solve (RelaxationRequest::deadline).
  Deadline deadline;
  // Anytime windows: when set, time_limit_s ends the search only once it holds an
  // incumbent; before its first one it runs on until the deadline (or max_nodes), so a
  // search given too short a share ends with a plan rather than none.
  bool time_limit_needs_incumbent = false;
  // While the search holds no plan, the QPs that complete its roundings (at the root and
  // on dives) may run this long past the deadline in force [s] (its stop flag still ends
  // them): a search whose root relaxation was solved in time ends with a plan whenever a
  // rounding of it gives one, rather than with none because the deadline passed between
  // the relaxation and its roundings. Once it holds a plan the deadline is kept exactly.
  double first_plan_overrun_s = 0.0;
  // Stall limit: with an incumbent, the search also ends (as at its time limit) once
  // this fraction of time_limit_s has passed since the incumbent last improved (0: off).
  // For receding windows whose proofs cannot finish in their share: the time a search
  // spends not improving its plan is better spent on the next window.
  double stall_time_fraction = 0.0;
  int max_nodes = 20000;
  double relative_gap = 1e-4;      // stop when (incumbent - bound) <= relative_gap * max(1, |incumbent|)
  double absolute_gap = 1e-6;
  double integrality_tolerance = 1e-5;
  double feasibility_tolerance = 1e-5;  // row/bound violation accepted in an incumbent
  NodeSelection node_selection = NodeSelection::kDiveThenBestBound;
  double plunge_fraction = 0.5;  // see kBestBoundWithPlunging
  BranchingRule branching = BranchingRule::kGroupOrder;
  int reliability = 2;              // kReliability: observations per direction to trust a pseudo-cost
  int strong_branching_candidates = 8;  // kReliability: most candidates strong-branched at a node
  int strong_branching_lookahead = 4;   // kReliability: stop after this many trials without a better score
  bool rounding_heuristic = true;  // round and solve the fixed QP at the root and on dives
  int rounding_frequency = 10;     // also try rounding every this many nodes (0 = root only)
  // The roundings' QPs are solved in order (a round of workers at a time) and none is
  // started once the search holds a plan, instead of completing them all: a quick plan
  // rather than the best rounding (relax-and-fix's dive).
  bool rounding_stops_at_first_plan = false;
  // Optional slow primal heuristic (relax-and-fix's seed), run once at the root with the
  // root relaxation point when rounding_heuristic is on, and only after the root's
  // roundings have been completed: the search holds their plan before this starts, so a
  // heuristic that takes the whole time limit cannot leave the search without a plan.
  // Returns assignments (a plan's own, typically); each is offered as it is and then
  // completed by its fixed-integer QP while time is left.
  std::function<std::vector<Eigen::VectorXd>(const Eigen::VectorXd& relaxed)> root_heuristic;
  // root_heuristic waits: when the search holds a plan once its root's roundings (and
  // first_plan_heuristic) are done, root_heuristic runs only after this many nodes, the
  // root included, and only if the search has not ended by then; it gets the root
  // relaxation point still. A search that ends sooner never runs it: a proof shorter than
  // this does not need the slow heuristic's plan. Without a plan after the root it runs
  // there, as with 0 (always at the root). The root cut loop's first pass runs it at the root.
  int root_heuristic_after_nodes = 0;
  // ... and it waits only when the root's plan is within this relative gap of the root
  // bound (RelativeGap): a poorer plan gets the heuristic's at once. Nor does it wait in a
  // search whose time left would not hold root_heuristic_after_nodes more nodes at its pace
  // so far (the root's): a window of a short time share would never reach the count.
  double root_heuristic_wait_gap = kInfinity;
  // Optional quick primal heuristic for a root whose roundings found no plan (relax-and-
  // fix's dive in the planner): run once at the root, after the roundings and before
  // root_heuristic, only when the search holds no incumbent yet; its plans are offered
  // and completed as root_heuristic's. A search whose roundings succeed never calls it.
  std::function<std::vector<Eigen::VectorXd>(const Eigen::VectorXd& relaxed)> first_plan_heuristic;
  bool bound_propagation = true;   // tighten bounds over the rows at every node first
  // After bound propagation, probe the open one-of groups (group_probing.h): each member
  // fixed in turn and propagated; members that cannot be 1 are ruled out and every bound
  // shrinks to the hull of the members' cases. The root's box is probed after its
  // roundings and heuristics (never before the first plan), a node's before its
  // relaxation; the bounds found are handed down to the node's subtree. On by default,
  // kept to long searches by long_search_only's default: fewer nodes to proof on Table I,
  // and a window whose time share holds only a few dozen nodes never pays a probed node's
  // higher cost (probing at every node ran more courses out of their window shares;
  // docs/measurements.md).
  bool group_probing = true;
  // Probe the nodes of depth 1, 1 + k, 1 + 2k, ... (k = this; the others inherit their
  // ancestors' probed bounds and propagate).
  int group_probing_interval = 1;
  // Work cap of one node's probing, in row visits per row of the problem (<= 0: none): the
  // sweep starts at the branched group and goes outwards along the list (the plan's
  // neighbouring steps first) and stops between groups once the cap is spent.
  double group_probing_work = 5.0;
  // RINS (rins.h; when it runs: RinsSchedule there and the options below; rins_frequency
  // 0: off): at a node (or at the root after its heuristics) the integers on which the
  // incumbent and the node's relaxation agree within
  // rins_agreement are fixed to the incumbent's values and the rest searched with at most
  // rins_max_nodes nodes; skipped when fewer than rins_min_fixed_fraction of the integers
  // (or all of them) agree. On by default, kept to long searches by long_search_only
  // (what it gives: docs/measurements.md, inc12).
  // The nodes between runs at first and after a run that improved the plan.
  int rins_frequency = 20;
  // The first run waits until the search has processed this many nodes since its plan
  // last improved (0: at the root): a search whose tree keeps finding better plans, or a
  // proof of a few hundred nodes, needs no sub-searches (as relax_and_fix.after_nodes
  // waits for the slow root heuristic).
  int rins_after_nodes = 200;
  // Each run that finds no plan better by more than the gap tolerance multiplies the
  // interval by this (1: a fixed interval); one that does restores rins_frequency. Runs
  // that keep failing thus cost a share of the nodes that shrinks as the search goes on.
  double rins_backoff = 2.0;
  // RINS runs only while the search's relative gap (incumbent to bound, as reported)
  // exceeds this: a plan this close to the bound leaves a sub-search little to find, and
  // its nodes would be the proof's.
  double rins_min_gap = 0.05;
  int rins_max_nodes = 200;
  // How the sub-searches choose their nodes. Depth first: a sub-search holds the incumbent
  // from its root, so best bound would spend its nodes raising the bound of a
  // neighbourhood instead of reaching its plans.
  NodeSelection rins_node_selection = NodeSelection::kDepthFirst;
  double rins_agreement = 0.1;
  double rins_min_fixed_fraction = 0.5;
  // Where the levers pay: a search is *long* at a moment when it has processed at least
  // long_search_min_nodes nodes and the time it has left (to the deadline in force, and
  // to its stall limit once it holds a plan) would hold at least long_search_nodes_left
  // more nodes at its mean time per node so far (its elapsed time over its nodes, the
  // root's heuristics included). A search whose time share holds only a few dozen nodes
  // (a receding window) is never long: the levers' cost per node would not be repaid.
  // The levers named in long_search_only (a sum of LongSearchLever values) run only while
  // the search is long; the others whenever they are on. Group probing and RINS by default.
  int long_search_min_nodes = 0;
  double long_search_nodes_left = 200.0;
  int long_search_only = kLongSearchProbing | kLongSearchRins;
  // Root cut loop (root_cuts.h): rounds of cut separation at the root (0: off). The root
  // is solved and its roundings and heuristics run first, on the problem as given, so the
  // loop never delays the first plan; then the loop (with reduced-cost fixing against that
  // plan), then the search on the problem with the cuts added as rows, holding that plan.
  // Its plans and optimum are those of the problem (the cuts are valid), its bound higher.
  int root_cut_rounds = 0;
  // The families the loop separates: a sum of RootCutFamily values.
  int root_cut_families = kAllRootCutFamilies;
  int root_cut_aggregations = 3;  // c-MIR: rows added to a starting row to cancel continuous variables
  int root_cuts_per_round = 100;        // most cuts added per round
  double root_cut_min_efficacy = 1e-4;  // violation per unit coefficient norm for a cut to count
  // The loop ends when a round raises the root bound by less than this fraction of |bound|.
  double root_cut_min_progress = 1e-4;
  // Reduced-cost fixing: when the relaxation solver certifies how fast the objective
  // grows away from a bound (RelaxationResult::cost_floor and rates), integer values
  // that cannot beat the incumbent are ruled out for the node's subtree.
  bool reduced_cost_fixing = true;
  // A node's relaxation may stop as soon as its solver proves that it cannot beat the
  // incumbent (RelaxationRequest::cutoff).
  bool early_cutoff = true;
  // Relative accuracy asked of each relaxation (RelaxationRequest::relative_tolerance)
  // when looser than the solver's own; 0: the solver's own.
  double relaxation_tolerance = 0.0;
  // Crossover of each relaxation (RelaxationRequest::polish_tolerance), off at 0: its
  // solver may finish from its active set once its residuals reach this relative accuracy.
  double relaxation_polish = 0.0;
  // Re-certification of lagging floors, off at 0 (the default: with 8 every window of the
  // 8 scenarios is certified and a window keeps its goal, but a real-scan walk decided by
  // re-certified local-goal windows still ends short: docs/measurements.md, stops 37-38). The search
  // keeps (boxes and relaxation points) the this-many lowest-floor subtrees it settled
  // below what its gap asks (pruned by their objectives, closed at an integral
  // point, strong-branching children); when its tree is exhausted short of the gap, it
  // solves them again, lowest floor first, with RelaxationRequest::certify_floor, raising
  // each floor to what the exact solve certifies, until the gap is met, each has been
  // solved once, or the deadline passes.
  int recertify_leaves = 0;
  // What re-certification keeps of the incumbent (optional): called once, with the
  // incumbent, when re-certification is about to solve its first subtree; returns ranges
  // of variables that the incumbent meets (empty: nothing to keep; ranges it does not
  // meet are ignored). From then on the search proves the problem within those ranges:
  // the kept subtrees' boxes are cut to them before their solves, so a subtree is
  // re-opened only when it can beat the incumbent within them, and no point outside them
  // becomes the incumbent (BranchAndBoundResult::restricted). Every floor settled before
  // stays a floor of the restricted problem, which is a part of the whole. A receding
  // window whose plan reaches the goal keeps its final feet within the goal's tolerance
  // (planner/planning/internal/goal_keeping.h): its objective rewards the goal without
  // demanding it, and a certified window must not trade the goal for a lower objective.
  std::function<std::vector<VariableRange>(const Eigen::VectorXd& incumbent)> recertify_within;
  // Optional: replaces a node's relaxation point x by one with more integral values that
  // is just as good (the caller knows where fractional values are only an artefact of
  // the encoding), within the node's bounds lower/upper; returns false when it changed
  // nothing. The search checks the new point (rows, bounds, objective no higher) and
  // branches on it, so no subtree is explored twice for a choice that does not matter.
  std::function<bool(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, Eigen::VectorXd* x)>
      equivalent_point;
  // Progress for logs: called with the result so far (incumbent objective, a valid bound,
  // gap, nodes, relaxations, elapsed time in solve_time_s; x left empty) each time the
  // incumbent improves.
  std::function<void(const BranchAndBoundResult&)> on_incumbent;
};

struct BranchAndBoundResult {
  SolveStatus status = SolveStatus::kNoSolution;
  Eigen::VectorXd x;            // incumbent (empty when none)
  double objective = kInfinity;  // incumbent objective, incl. constant
  double bound = -kInfinity;     // proven lower bound
  double root_bound = -kInfinity;  // the root relaxation's bound (after propagation and root cuts)
  double root_bound_before_cuts = -kInfinity;  // the root relaxation's bound before the cut loop (when it ran)
  int root_cuts = 0;                           // cut rows added by the root cut loop
  double gap = kInfinity;        // (objective - bound) / max(1, |objective|)
  int nodes = 0;
  int relaxations = 0;
  int propagation_prunes = 0;   // nodes found infeasible by bound propagation alone
  int strong_branching_solves = 0;  // relaxations solved to score branching candidates
  int reduced_cost_fixings = 0;     // integer bounds tightened by reduced-cost fixing
  int early_cutoffs = 0;            // node relaxations stopped once they could not beat the incumbent
  int equivalent_points = 0;        // relaxation points replaced by options.equivalent_point
  int probed_nodes = 0;             // nodes probed (options.group_probing) that went on to branch
  int rins_runs = 0;                // RINS sub-searches run (options.rins_frequency)
  int rins_improvements = 0;        // of them, those that found a better incumbent
  int rins_nodes = 0;               // nodes of the RINS sub-searches (not counted in nodes)
  // The nodes' own relaxation solves (not the heuristics' QPs nor strong branching): their
  // solver iterations and wall time, for the time per node and iterations per node.
  long node_solve_iterations = 0;
  double node_solve_time_s = 0.0;
  // Relaxations the solver's primary method could not finish, solved again by its
  // fallback (RelaxationResult::fallbacks): of the nodes' own solves (the root included),
  // and of all the search's solves (nodes, roundings, strong branching, root cuts), with
  // the wall time of the latter [s].
  int node_fallbacks = 0;
  int fallbacks = 0;
  // The nodes' own solves the crossover finished (RelaxationResult::polished), and the
  // active sets it tried on them: attempts - polished is its fallbacks to the solver's method.
  int node_polished = 0;
  int node_polish_attempts = 0;
  // Settled subtrees solved again to certify their floors (options.recertify_leaves), also
  // counted in relaxations, and how many of them now meet the gap.
  int floor_recertifications = 0;
  int floors_certified = 0;
  // The bound and the status hold over the problem within options.recertify_within's
  // ranges (re-certification restricted the search to them); false: over the whole problem.
  bool restricted = false;
  double fallback_time_s = 0.0;
  double solve_time_s = 0.0;
};

// Adds a relaxation's fallback statistics to the search's (fallbacks, fallback_time_s).
inline void CountFallbacks(const RelaxationResult& relaxation, BranchAndBoundResult* result) {
  result->fallbacks += relaxation.fallbacks;
  result->fallback_time_s += relaxation.fallback_time_s;
}

// Heuristic hook: given a relaxation point, propose assignments of the integer variables
// (each a vector over all variables; only integer entries are used). The branch-and-bound
// fixes the integers of each proposal and solves the remaining convex QP. The footstep
// formulation supplies proposals that follow the step order.
using RoundingHeuristic = std::function<std::vector<Eigen::VectorXd>(const Eigen::VectorXd& relaxed)>;

BranchAndBoundResult SolveBranchAndBound(const Miqp& problem, RelaxationSolver& solver,
                                         const BranchAndBoundOptions& options,
                                         const RoundingHeuristic& extra_rounding = {});

// The same search with one relaxation solver per worker: each round takes up to
// solvers.size() open nodes and solves their relaxations on threads of their own (the
// solvers must not share state). Heuristics and strong branching use solvers[0].
BranchAndBoundResult SolveBranchAndBound(const Miqp& problem, const std::vector<RelaxationSolver*>& solvers,
                                         const BranchAndBoundOptions& options,
                                         const RoundingHeuristic& extra_rounding = {});

}  // namespace mfp
