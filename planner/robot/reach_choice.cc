#include "planner/robot/internal/reach_choice.h"

#include <string>

#include "base/check.h"
#include "planner/robot/internal/footprint_polygon.h"

namespace mfp {

ReachChoice ChooseReach(const std::vector<LegDerivation>& legs, const std::vector<std::string>& leg_names,
                        double cell_m, const DerivationOptions& options) {
  MFP_CHECK(leg_names.size() == legs.size());
  ReachChoice choice;
  choice.shape = options.reach_shape;
  const bool given = !options.reach_shape_given.empty();
  choice.why = given ? "given " + options.reach_shape_given
               : choice.shape != DerivationOptions{}.reach_shape
                   ? std::string("chosen")
                   : std::string("the default for a robot derived from a URDF: each leg's own footprint polygon, "
                                 "turned with the body, lies in its reachable footprint at every body yaw and keeps "
                                 "the footprint's reach forward and back");
  if (choice.shape != ReachShape::kFootprint) return choice;
  for (size_t k = 0; k < legs.size(); ++k) {
    try {
      choice.faces.push_back(
          FootprintPolygon(legs[k].footprint, legs[k].nominal_foot_body_m.head<2>(), options.footprint_faces));
      // Each face pulled in by half a cell must still pass in front of the nominal foot, or
      // the polygon no longer holds it.
      for (ReachFace& f : choice.faces.back()) {
        f.offset_m -= 0.5 * cell_m;
        if (f.offset_m <= 0.0) {
          throw InputError("the footprint polygon of leg '" + leg_names[k] + "' is not wider than half a footprint "
                           "cell (" + std::to_string(0.5 * cell_m) + " m) about its nominal foot");
        }
      }
    } catch (const InputError& e) {
      if (given) throw;
      choice.shape = ReachShape::kHexadecagon;
      choice.faces.clear();
      choice.why = "the default's fallback: no footprint polygon fits leg '" + leg_names[k] + "' (" + e.what() +
                   "), and the 16-gon lies in every leg's reachable footprint at every body yaw";
      return choice;
    }
  }
  return choice;
}

}  // namespace mfp
