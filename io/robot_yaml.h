#pragma once
// Loads config/robots/NAME.yaml into a RobotModel. Two forms:
//  - with `urdf: FILE` (relative to the YAML): legs, nominal offsets and reach limits are
//    derived from the URDF (robot_derivation.h); the YAML may name the foot links
//    (`feet: [link, ...]`), fix `stance_height`, and give what a URDF cannot say (gait,
//    foot radius, max slope, weights) and the reach polygon (`reach_shape`; without it each
//    leg's footprint polygon, DerivationOptions' default, or the 16-gon when the file
//    overrides d_lim or l_bnd, which the footprint polygons would not follow; a stated
//    footprint with either override is an InputError). Any limit it gives (d_lim, l_bnd, dz_max,
//    max_yaw_change, foot_radius) overrides the derived value, and the provenance line
//    says so: "d_lim = 0.0700 m: override in littledog.yaml (derived 0.0640 m)". l_bnd and
//    max_yaw_change follow an overridden d_lim unless they are overridden themselves.
//  - without it: hand-written legs (nominal offsets) and limits, all required; the reach
//    polygon is the paper's box unless `reach_shape` says otherwise.
// Every value is recorded in provenance.
#include <optional>
#include <string>
#include <vector>

#include "base/deadline.h"
#include "io/option_table.h"
#include "planner/robot/robot_derivation.h"
#include "planner/robot/robot_model.h"

namespace mfp {

// Throws InputError naming the file, key and allowed range on bad input. When
// `derivation` is given and the YAML names a URDF, it receives the derivation details
// (footprints, nominal joint positions) with its model equal to the returned one. A URDF's
// derivation runs by `deadline` (TimeLimitError once it expires).
// `reach_shape`, when given, replaces the YAML's reach_shape key.
RobotModel LoadRobotYaml(const std::string& path, RobotDerivation* derivation = nullptr,
                         const Deadline& deadline = Deadline(), std::optional<ReachShape> reach_shape = std::nullopt);

// The keys of a robot YAML, for the reference.
std::vector<OptionDoc> RobotOptionDocs();

}  // namespace mfp
