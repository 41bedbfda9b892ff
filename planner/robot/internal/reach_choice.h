#pragma once
// Which reach polygon a robot derived from a URDF gets (robot_derivation.h): the options'
// shape, and for the footprint shape each leg's polygon about its nominal foot
// (footprint_polygon.h). Plain Eigen, no I/O.
#include <string>
#include <vector>

#include "planner/robot/robot_derivation.h"
#include "planner/robot/robot_model.h"

namespace mfp {

struct ReachChoice {
  ReachShape shape = ReachShape::kBox;
  std::string why;                            // for the reach_shape provenance line: who chose it
  std::vector<std::vector<ReachFace>> faces;  // per leg, faces pulled in by half a cell; empty unless kFootprint
};

// options.reach_shape, except that the default footprint falls back to the 16-gon when some
// leg's footprint holds no polygon about its nominal foot (why then names the leg): a URDF
// robot must not become unplannable by the default. A stated footprint (reach_shape_given)
// is the caller's choice and throws InputError instead. (Where DeriveRobot's legs stand,
// each with an inscribed square wider than a cell, a face along an axis, as the default's 12
// have, always clears each empty cell: the fallback guards face counts without such faces
// and future footprint rules.) leg_names[k] names legs[k]; cell_m is the footprints' cell.
ReachChoice ChooseReach(const std::vector<LegDerivation>& legs, const std::vector<std::string>& leg_names,
                        double cell_m, const DerivationOptions& options);

}  // namespace mfp
