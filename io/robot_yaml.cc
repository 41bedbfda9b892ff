#include "io/robot_yaml.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "base/check.h"
#include "base/format.h"
#include "io/option_table.h"
#include "io/yaml_fields.h"
#include "planner/robot/derivation_budget.h"
#include "planner/robot/urdf_reader.h"

namespace mfp {
namespace {

// The robot's scalar limits a YAML may give: required in the hand-written form, visible
// overrides of the derived values in the URDF form. One table, so both forms accept the
// same keys and ranges.
struct LimitField {
  const char* key;
  double RobotModel::*member;
  double min, max;
  const char* unit;
  bool required_without_urdf;
  bool derived;  // derived from the URDF (stance_height is an input of the derivation)
  const char* description;
};
const LimitField kLimitFields[] = {
    {"stance_height", &RobotModel::stance_height_m, 0.0, 10.0, "m", false, false,
     "body height above the feet when standing (URDF form: an input of the derivation)"},
    {"foot_radius", &RobotModel::foot_radius_m, 0.0, 1.0, "m", false, true, "radius of a foot's contact"},
    {"d_lim", &RobotModel::d_lim_m, 1e-4, 10.0, "m", true, true,
     "half-width on x and y of a foot's reach polygon (reach_shape) about its previous nominal spot"},
    {"l_bnd", &RobotModel::l_bnd_m, 1e-4, 10.0, "m", true, true,
     "half-width of the box a foot keeps about the centre of contacts"},
    {"dz_max", &RobotModel::dz_max_m, 1e-4, 10.0, "m", true, true, "largest height change of one step"},
    {"max_yaw_change", &RobotModel::max_yaw_change_rad, 1e-3, M_PI, "rad", true, true,
     "largest body yaw change between configurations"},
    {"max_slope", &RobotModel::max_slope_rad, 0.0, M_PI / 2, "rad", false, true, "steepest surface a foot stands on"},
};

using option_table_internal::FormatNumber;
using option_table_internal::FormatRange;

// The reach limit a URDF robot's file overrides (d_lim, then l_bnd), or nullptr.
const char* ReachLimitOverride(const YAML::Node& root) {
  if (root["d_lim"]) return "d_lim";
  if (root["l_bnd"]) return "l_bnd";
  return nullptr;
}

// A footprint robot's reach rows are its legs' polygons, which no d_lim or l_bnd bounds: an
// override of either would be shown in the provenance and not kept by any step.
void RefuseReachLimitOverride(const YAML::Node& root, const YamlContext& ctx) {
  const char* limit = ReachLimitOverride(root);
  if (limit == nullptr) return;
  throw InputError(ctx.Child(limit).Where() + ": reach_shape footprint takes each leg's reach from its URDF "
                   "footprint, which a " + std::string(limit) + " override cannot bound; remove " + limit +
                   " or state reach_shape: hexadecagon (its reach follows d_lim and l_bnd)");
}

// The keys of a robot YAML: the loaders below read each; the limits come from kLimitFields.
OptionTable<RobotModel> MakeRobotOptionTable() {
  using R = RobotModel;
  OptionTable<R> t = {
      LoaderOpt<R>("name", "string", "\"robot\" (URDF form: the URDF's name)", "name requests and logs use"),
      LoaderOpt<R>("urdf", "path", "-", "derive legs and limits from this URDF, relative to the YAML"),
      LoaderOpt<R>("feet", "list of link names", "the URDF's leaf links", "URDF form: the foot links"),
      LoaderOpt<R>("foot_offset", "[x, y, z]", "[0, 0, 0]", "URDF form: the foot point in each foot link").Unit("m"),
      LoaderOpt<R>("forward", "one of x, y, -x, -y", "x", "URDF form: the URDF axis the robot walks along"),
      LoaderOpt<R>("legs", "list of legs", "(required without urdf)", "hand-written form: the legs"),
      LoaderOpt<R>("legs[].name", "string", "legK", "name of the leg"),
      LoaderOpt<R>("legs[].nominal_offset", "[x, y]", "(required)", "foot in the body frame when standing").Unit("m"),
      LoaderOpt<R>("legs[].hip", "[x, y, z]", "-", "hip in the body frame").Unit("m"),
      LoaderOpt<R>("gait", "list of leg names or indices", "leg order", "cyclic order in which the legs move"),
      LoaderOpt<R>("reach_shape", "one of box, octagon, hexadecagon, footprint",
                   "footprint (URDF form; hexadecagon with a d_lim override or where no polygon fits a leg); "
                   "box (hand-written form)",
                   "a foot's reach polygon about its previous nominal spot, d_lim its half-width on each axis: the "
                   "paper's box, the octagon with |dx +- dy| <= sqrt(2) d_lim, or the regular 16-gon of apothem "
                   "d_lim (URDF form: the octagon and the 16-gon are derived inside the footprint's disk about the "
                   "nominal foot, so they hold at every body yaw; the box does not); footprint (URDF form only): "
                   "each leg's own footprint polygon, turned with the body, about both its previous and its own "
                   "nominal spot (stated: an error where no polygon fits a leg's nominal foot)"),
  };
  for (const LimitField& f : kLimitFields) {
    const std::string range = "number in " + FormatRange(OptionKind::kDouble, f.min, f.max, false);
    const std::string when = f.required_without_urdf ? "(required without urdf)" : "-";
    t.push_back(LoaderOpt<R>(f.key, range, f.derived ? "derived from the URDF; " + when : when, f.description)
                    .Unit(f.unit));
  }
  t.push_back(LoaderOpt<R>("body_box.min", "[x, y]", "derived from the URDF; else none",
                           "rear-right corner of the body's plan box about the centre of contacts").Unit("m"));
  t.push_back(LoaderOpt<R>("body_box.max", "[x, y]", "derived from the URDF; else none",
                           "front-left corner of the body's plan box about the centre of contacts").Unit("m"));
  t.push_back(LoaderOpt<R>("body_box.bottom", "number in [0, 10]", "derived from the URDF; else none",
                           "lowest point of the body above the feet when standing").Unit("m"));
  t.push_back(LoaderOpt<R>("body_box.top", "number in [0, 10]", "derived from the URDF; else none",
                           "highest point of the body above the feet when standing").Unit("m"));
  const PlannerWeights w;
  t.push_back(LoaderOpt<R>("weights.goal_position", "number in [1e-06, 1e+09]", FormatNumber(w.goal_position),
                           "cost per m^2 of final-stance foot error").Advanced());
  t.push_back(LoaderOpt<R>("weights.goal_yaw", "number in [0, 1e+09]", FormatNumber(w.goal_yaw),
                           "cost per rad^2 of final yaw error").Advanced());
  t.push_back(LoaderOpt<R>("weights.trim_step", "number in [-1e+09, 0]", FormatNumber(w.trim_step),
                           "cost per trimmed step (negative: rewards shorter plans)").Advanced());
  t.push_back(LoaderOpt<R>("weights.displacement", "number in [0, 1e+09]", FormatNumber(w.displacement),
                           "cost per m^2 of centre-of-contacts motion between configurations").Advanced());
  return t;
}

const OptionTable<RobotModel>& RobotOptionTable() {
  static const OptionTable<RobotModel> table = MakeRobotOptionTable();
  return table;
}

std::string Describe(const std::string& key, double value, const std::string& unit,
                     const std::string& file) {
  std::ostringstream out;
  out << key << " = " << value << " " << unit << ": from " << file;
  return out.str();
}

// Gait entries may be leg indices or leg names.
std::vector<int> ReadGait(const YAML::Node& node, const YamlContext& ctx,
                          const std::vector<LegModel>& legs) {
  if (!node.IsSequence()) throw InputError(ctx.Where() + ": expected a list of legs");
  std::vector<int> gait;
  for (size_t i = 0; i < node.size(); ++i) {
    const YamlContext at = ctx.Index(i);
    const std::string text = ReadString(node[i], at);
    int index = -1;
    for (size_t k = 0; k < legs.size(); ++k) {
      if (legs[k].name == text) index = static_cast<int>(k);
    }
    if (index < 0) index = ReadInt(node[i], at, 0, static_cast<int>(legs.size()) - 1);
    gait.push_back(index);
  }
  return gait;
}


// Replaces the provenance line of `key` ("key = ...") or appends one.
void SetProvenance(RobotModel* robot, const std::string& key, const std::string& line) {
  for (std::string& existing : robot->provenance) {
    if (existing.rfind(key + " =", 0) == 0) {
      existing = line;
      return;
    }
  }
  robot->provenance.push_back(line);
}

// reach_shape: box, octagon, hexadecagon or footprint, `fallback` when absent; `given` (the caller's)
// replaces the key.
ReachShape ReadReachShape(const YAML::Node& root, const YamlContext& ctx, std::optional<ReachShape> given,
                          ReachShape fallback) {
  const std::optional<std::string> text = OptionalString(root, ctx, "reach_shape");
  if (given) return *given;
  if (!text) return fallback;
  for (ReachShape shape : {ReachShape::kBox, ReachShape::kOctagon, ReachShape::kHexadecagon, ReachShape::kFootprint}) {
    if (*text == ReachShapeName(shape)) return shape;
  }
  throw InputError(ctx.Child("reach_shape").Where() + ": '" + *text +
                   "' is not one of box, octagon, hexadecagon, footprint");
}

void ReadWeights(const YAML::Node& root, const YamlContext& ctx, PlannerWeights* weights) {
  if (!root["weights"]) return;
  const YAML::Node w = root["weights"];
  const YamlContext wctx = ctx.Child("weights");
  RejectUnknownKeys(w, wctx, {"goal_position", "goal_yaw", "trim_step", "displacement"});
  weights->goal_position =
      OptionalDouble(w, wctx, "goal_position", 1e-6, 1e9).value_or(weights->goal_position);
  weights->goal_yaw = OptionalDouble(w, wctx, "goal_yaw", 0.0, 1e9).value_or(weights->goal_yaw);
  weights->trim_step =
      OptionalDouble(w, wctx, "trim_step", -1e9, 0.0).value_or(weights->trim_step);
  weights->displacement =
      OptionalDouble(w, wctx, "displacement", 0.0, 1e9).value_or(weights->displacement);
}

// body_box: every key optional, each overriding the derived (or unknown) value; the
// result must be a box with min < max and bottom < top.
void ReadBodyBox(const YAML::Node& root, const YamlContext& ctx, RobotModel* robot) {
  if (!root["body_box"]) return;
  const YAML::Node node = root["body_box"];
  const YamlContext bctx = ctx.Child("body_box");
  if (!node.IsMap()) throw InputError(bctx.Where() + ": expected a mapping {min, max, bottom, top}");
  BodyExtent& body = robot->body;
  for (const char* corner : {"min", "max"}) {
    if (!node[corner]) continue;
    const auto v = ReadNumbers(node[corner], bctx.Child(corner), 2);
    (std::string(corner) == "min" ? body.min_m : body.max_m) = Eigen::Vector2d(v[0], v[1]);
  }
  body.bottom_m = OptionalDouble(node, bctx, "bottom", 0.0, 10.0).value_or(body.bottom_m);
  body.top_m = OptionalDouble(node, bctx, "top", 0.0, 10.0).value_or(body.top_m);
  if (!body.known()) {
    throw InputError(bctx.Where() + ": the body box needs min < max on x and y and bottom < top (m); give all "
                     "four keys where the URDF gives no body box");
  }
  SetProvenance(robot, "body box",
                "body box = x [" + Fixed(body.min_m.x()) + ", " + Fixed(body.max_m.x()) + "] m, y [" +
                    Fixed(body.min_m.y()) + ", " + Fixed(body.max_m.y()) + "] m about the centre of contacts, " +
                    Fixed(body.bottom_m) + " to " + Fixed(body.top_m) + " m above the feet: from " + ctx.file);
}

// The URDF form: derive, then apply the YAML's values as visible overrides.
RobotModel LoadUrdfYaml(const YAML::Node& root, const YamlContext& ctx, const std::string& path,
                        RobotDerivation* derivation_out, const Deadline& deadline,
                        std::optional<ReachShape> reach_shape) {
  if (root["legs"]) {
    throw InputError(ctx.Child("legs").Where() +
                     ": not allowed with urdf (the URDF gives the legs; name the foot links "
                     "with feet: [...])");
  }
  const std::string urdf_path =
      ResolveRelative(path, ReadString(root["urdf"], ctx.Child("urdf")));
  std::vector<std::string> feet;
  if (root["feet"]) {
    const YamlContext fctx = ctx.Child("feet");
    if (!root["feet"].IsSequence() || root["feet"].size() == 0) {
      throw InputError(fctx.Where() + ": expected a non-empty list of link names");
    }
    for (size_t i = 0; i < root["feet"].size(); ++i) {
      feet.push_back(ReadString(root["feet"][i], fctx.Index(i)));
    }
  }
  std::optional<Eigen::Vector3d> foot_offset;
  if (root["foot_offset"]) {
    const auto v = ReadNumbers(root["foot_offset"], ctx.Child("foot_offset"), 3);
    foot_offset = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  RobotDescription description = ReadUrdfRobot(urdf_path, feet, foot_offset);
  if (foot_offset) {
    description.notes.push_back("foot point (" + Fixed((*foot_offset)[0]) + ", " + Fixed((*foot_offset)[1]) +
                                ", " + Fixed((*foot_offset)[2]) + ") m in each foot link: foot_offset in " + ctx.file);
  }
  if (root["forward"]) {
    const std::string forward = ReadString(root["forward"], ctx.Child("forward"));
    const std::map<std::string, double> kYaw = {{"x", 0.0}, {"y", M_PI / 2}, {"-x", M_PI}, {"-y", -M_PI / 2}};
    const auto it = kYaw.find(forward);
    if (it == kYaw.end()) {
      throw InputError(ctx.Child("forward").Where() + ": '" + forward + "' is not one of x, y, -x, -y (the URDF "
                       "axis the robot walks along)");
    }
    TurnForwardToX(&description, it->second);
    description.notes.push_back("forward: the URDF's " + forward + " axis (forward in " + ctx.file + ")");
  }
  DerivationOptions options;
  options.stance_height_m = OptionalDouble(root, ctx, "stance_height", 1e-4, 10.0);
  options.reach_shape = ReadReachShape(root, ctx, reach_shape, options.reach_shape);
  if (reach_shape) {
    options.reach_shape_given = "by the caller";
  } else if (root["reach_shape"]) {
    options.reach_shape_given = "in " + path;
  } else if (const char* limit = ReachLimitOverride(root)) {
    // The footprint polygons are derived from the legs alone and would not follow a d_lim or
    // l_bnd override: the 16-gon, whose reach d_lim and l_bnd are, keeps the file's limits.
    options.reach_shape = ReachShape::kHexadecagon;
    options.reach_shape_given = std::string("by the ") + limit + " override in " + path +
                                " (a footprint polygon would not follow it)";
  }
  if (options.reach_shape == ReachShape::kFootprint) RefuseReachLimitOverride(root, ctx);
  options = WithinDerivationBudget(options, &description);
  options.deadline = deadline;
  RobotDerivation derivation = DeriveRobot(description, options);
  RobotModel& robot = derivation.model;
  const std::string file = ctx.file;
  if (options.stance_height_m) {
    SetProvenance(&robot, "stance_height",
                  "stance_height = " + Fixed(robot.stance_height_m) + " m: given in " + file +
                      " (not derived)");
  }
  if (const auto name = OptionalString(root, ctx, "name")) robot.name = *name;

  const double derived_d_lim = robot.d_lim_m;
  for (const LimitField& f : kLimitFields) {
    if (!f.derived) continue;  // stance_height is handled above, before the derivation
    const auto value = OptionalDouble(root, ctx, f.key, f.min, f.max);
    if (!value) continue;
    double& field = robot.*f.member;
    const std::string derived = Fixed(field);
    field = *value;
    SetProvenance(&robot, f.key,
                  std::string(f.key) + " = " + Fixed(*value) + " " + f.unit + ": override in " +
                      file + " (derived " + derived + " " + f.unit + ")");
  }
  if (robot.d_lim_m != derived_d_lim) {
    // Values derived from d_lim follow its override unless overridden themselves.
    if (!root["l_bnd"]) {
      const double fraction = options.l_bnd_fraction;
      robot.l_bnd_m = fraction * robot.d_lim_m;
      SetProvenance(&robot, "l_bnd",
                    "l_bnd = " + Fixed(robot.l_bnd_m) + " m: derived, " + Fixed(fraction) +
                        " * d_lim (the override in " + file + ")");
    }
    if (!root["max_yaw_change"]) {
      const double max_leg = LegReach(robot);
      robot.max_yaw_change_rad = MaxYawChangeFor(robot.d_lim_m, max_leg);
      SetProvenance(&robot, "max_yaw_change",
                    "max_yaw_change = " + Fixed(robot.max_yaw_change_rad) +
                        " rad: derived, 2 asin(d_lim / (2 * " + Fixed(max_leg) +
                        " m)) with the d_lim override in " + file);
    }
  }
  if (root["gait"]) {
    robot.gait = ReadGait(root["gait"], ctx.Child("gait"), robot.legs);
    std::string names;
    for (int g : robot.gait) names += (names.empty() ? "" : ", ") + robot.legs[g].name;
    SetProvenance(&robot, "gait", "gait = [" + names + "]: override in " + file);
  }
  if (root["weights"]) {
    ReadWeights(root, ctx, &robot.weights);
    SetProvenance(&robot, "weights", "weights: from " + file);
  }
  ReadBodyBox(root, ctx, &robot);
  ValidateRobotModel(robot);
  RobotModel result = robot;
  if (derivation_out != nullptr) *derivation_out = std::move(derivation);
  return result;
}

}  // namespace

static RobotModel LoadRobotYamlUnguarded(const std::string& path, RobotDerivation* derivation,
                                         const Deadline& deadline, std::optional<ReachShape> reach_shape) {
  const YAML::Node root = LoadYamlFile(path);
  const YamlContext ctx{path, ""};
  RobotModel unread;
  ReadOptions(RobotOptionTable(), root, ctx, &unread);  // checks the keys; all are read below
  if (root["urdf"]) return LoadUrdfYaml(root, ctx, path, derivation, deadline, reach_shape);
  if (derivation != nullptr) *derivation = RobotDerivation{};
  for (const char* key : {"feet", "foot_offset", "forward"}) {
    if (root[key]) throw InputError(ctx.Child(key).Where() + ": only allowed together with urdf");
  }
  RobotModel robot;
  robot.name = OptionalString(root, ctx, "name").value_or("robot");
  if (!root["legs"] || !root["legs"].IsSequence() || root["legs"].size() == 0) {
    throw InputError(ctx.Child("legs").Where() + ": expected a non-empty list of legs");
  }
  const YamlContext legs_ctx = ctx.Child("legs");
  for (size_t k = 0; k < root["legs"].size(); ++k) {
    const YAML::Node leg_node = root["legs"][k];
    const YamlContext leg_ctx = legs_ctx.Index(k);
    RejectUnknownKeys(leg_node, leg_ctx, {"name", "nominal_offset", "hip"});
    LegModel leg;
    leg.name = OptionalString(leg_node, leg_ctx, "name").value_or("leg" + std::to_string(k));
    if (!leg_node["nominal_offset"]) {
      throw InputError(leg_ctx.Child("nominal_offset").Where() + ": missing (x, y in metres)");
    }
    const auto offset =
        ReadNumbers(leg_node["nominal_offset"], leg_ctx.Child("nominal_offset"), 2);
    leg.nominal_offset_body_m = Eigen::Vector2d(offset[0], offset[1]);
    if (leg_node["hip"]) {
      const auto hip = ReadNumbers(leg_node["hip"], leg_ctx.Child("hip"), 3);
      leg.hip_body_m = Eigen::Vector3d(hip[0], hip[1], hip[2]);
    }
    robot.legs.push_back(leg);
  }
  if (root["gait"]) {
    robot.gait = ReadGait(root["gait"], ctx.Child("gait"), robot.legs);
  } else {
    for (int k = 0; k < robot.num_legs(); ++k) robot.gait.push_back(k);
  }

  for (const LimitField& f : kLimitFields) {
    const auto value = OptionalDouble(root, ctx, f.key, f.min, f.max);
    if (value) {
      robot.*f.member = *value;
      robot.provenance.push_back(Describe(f.key, *value, f.unit, path));
    } else if (f.required_without_urdf) {
      throw InputError(ctx.Child(f.key).Where() + ": missing (allowed range [" +
                       std::to_string(f.min) + ", " + std::to_string(f.max) + "] " + f.unit + ")");
    }
  }
  robot.reach_shape = ReadReachShape(root, ctx, reach_shape, ReachShape::kBox);
  robot.provenance.push_back(std::string("reach_shape = ") + ReachShapeName(robot.reach_shape) + ": " +
                             (reach_shape ? std::string("given by the caller")
                              : root["reach_shape"] ? "from " + path
                                                    : std::string("the paper's box, the default")));
  ReadWeights(root, ctx, &robot.weights);
  ReadBodyBox(root, ctx, &robot);
  for (size_t k = 0; k < robot.legs.size(); ++k) {
    const Eigen::Vector2d o = robot.legs[k].nominal_offset_body_m;
    std::ostringstream out;
    out << "legs[" << k << "] '" << robot.legs[k].name << "' nominal offset (" << o.x() << ", "
        << o.y() << ") m, L_leg " << o.norm() << " m, phi " << std::atan2(o.y(), o.x())
        << " rad: from " << path;
    robot.provenance.push_back(out.str());
  }
  ValidateRobotModel(robot);
  return robot;
}

RobotModel LoadRobotYaml(const std::string& path, RobotDerivation* derivation, const Deadline& deadline,
                         std::optional<ReachShape> reach_shape) {
  return GuardYaml(path, [&] { return LoadRobotYamlUnguarded(path, derivation, deadline, reach_shape); });
}

std::vector<OptionDoc> RobotOptionDocs() {
  return DocumentOptions(RobotOptionTable(), "", RobotModel{});
}

}  // namespace mfp
