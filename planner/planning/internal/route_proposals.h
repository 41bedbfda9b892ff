#pragma once
// Route-following proposals for a guided window: integer assignments that walk the body
// route (route_guide.h) at a few speeds, offered to the window's search at its root.
//
// On fields of many small regions (an uneven field of cells, dense stepping stones) a
// window of two configurations has hundreds of region binaries; its search runs out of
// its time share long before a proof and keeps the first plans its dives find, which
// move the body a fraction of d_lim per configuration. A plan that simply follows the
// route is a far better incumbent: each new step's foot is put at the leg's nominal spot
// for the body pose the route reaches by that step (the body moving `advance` per
// configuration, the yaw turning toward a target at most max_yaw_change per
// configuration), and MiqpFormulation::RoundAlongPlan chooses the region holding that
// spot (or the nearest) and the yaw segments. The search solves each proposal's QP with
// its integers fixed and keeps the best feasible one; one that fits nowhere costs a QP.
// No I/O.
#include <Eigen/Core>
#include <vector>

#include "planner/formulation/miqp_formulation.h"
#include "planner/planning/internal/route_guide.h"

namespace mfp {

struct RouteProposalOptions {
  // Body advance per configuration, as fractions of d_lim. On an uneven field of cells the
  // full speed rarely fits (a foot moved into its cell breaks the reach box) and 0.6
  // mostly does; the search keeps the feasible proposal of least cost.
  std::vector<double> advance_fractions = {1.0, 0.6, 0.3};
  // Yaw turns toward its target by at most this fraction of max_yaw_change per configuration.
  double yaw_rate_fraction = 0.8;
};

// Proposals (vectors over all of formulation.miqp()'s variables; only the integer entries
// matter) for the formulation's window, whose start stance lies at route arc length
// progress_m. For each advance: the yaw held, turned toward the route's heading, and
// turned toward the goal yaw (duplicates dropped). Empty when the guide has no route.
std::vector<Eigen::VectorXd> RouteProposals(const MiqpFormulation& formulation, const RouteGuide& guide,
                                            double progress_m, const RouteProposalOptions& options = {});

}  // namespace mfp
