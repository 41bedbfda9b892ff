#include "planner/robot/urdf_reader.h"

#include <console_bridge/console.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "base/check.h"
#include "planner/robot/internal/urdf_body.h"
#include "planner/robot/internal/urdf_xml_checks.h"

namespace mfp {
namespace {

// Collects urdfdom's console messages so that they end up in our error, not on stderr.
class CaptureConsole : public console_bridge::OutputHandler {
 public:
  CaptureConsole() { console_bridge::useOutputHandler(this); }
  ~CaptureConsole() override { console_bridge::restorePreviousOutputHandler(); }
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) {
      messages_ += (messages_.empty() ? "" : "; ") + text;
    }
  }
  const std::string& messages() const { return messages_; }

 private:
  std::string messages_;
};

JointModel ToJointModel(const urdf::Joint& joint, const std::string& path,
                        std::vector<std::string>* notes) {
  const std::string where = path + ": joint '" + joint.name + "'";
  JointModel model;
  model.name = joint.name;
  model.T_parent_joint = ToIsometry(joint.parent_to_joint_origin_transform);
  switch (joint.type) {
    case urdf::Joint::FIXED:
      model.type = JointModel::Type::kFixed;
      return model;
    case urdf::Joint::REVOLUTE:
    case urdf::Joint::CONTINUOUS:
      model.type = JointModel::Type::kRevolute;
      break;
    case urdf::Joint::PRISMATIC:
      model.type = JointModel::Type::kPrismatic;
      break;
    default:
      throw InputError(where + ": type floating/planar/unknown is not supported in a leg "
                               "(allowed: revolute, continuous, prismatic, fixed)");
  }
  const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
  const double norm = axis.norm();
  if (!(norm > 1e-9)) {
    throw InputError(where + ": axis has zero length (needs a non-zero direction)");
  }
  model.axis = axis / norm;
  if (joint.type == urdf::Joint::CONTINUOUS) {
    model.lower = -M_PI;
    model.upper = M_PI;
    if (notes) notes->push_back("joint '" + joint.name + "': continuous, sampled over [-pi, pi] rad (one turn)");
    return model;
  }
  if (!joint.limits) throw InputError(where + ": missing <limit lower upper>");
  model.lower = joint.limits->lower;
  model.upper = joint.limits->upper;
  if (!(model.lower <= model.upper)) {
    std::ostringstream msg;
    msg << where << ": limit lower = " << model.lower << " is above upper = " << model.upper
        << " (needs lower <= upper)";
    throw InputError(msg.str());
  }
  // Placeholder limits (+-10 rad, +-1e16) wider than a turn: one turn about the middle of
  // the range, which covers every distinct pose of the joint.
  if (model.type == JointModel::Type::kRevolute && model.upper - model.lower > 2.0 * M_PI) {
    std::ostringstream note;
    note << "joint '" << joint.name << "': limits [" << model.lower << ", " << model.upper
         << "] rad span more than a turn; ";
    const double mid = std::abs(model.upper + model.lower) < 1e6 ? 0.5 * (model.upper + model.lower) : 0.0;
    model.lower = mid - M_PI;
    model.upper = mid + M_PI;
    note << "sampled over [" << model.lower << ", " << model.upper << "] rad";
    if (notes) notes->push_back(note.str());
  }
  return model;
}

std::string TrimSeparators(std::string s) {
  while (!s.empty() && (s.back() == '_' || s.back() == '-')) s.pop_back();
  return s;
}

std::string CommonPrefixName(const std::vector<std::string>& names) {
  if (names.empty()) return "";
  std::string prefix = names.front();
  for (const std::string& n : names) {
    size_t i = 0;
    while (i < prefix.size() && i < n.size() && prefix[i] == n[i]) ++i;
    prefix.resize(i);
  }
  return TrimSeparators(prefix);
}

// The chain's common suffix when it has no common prefix ("abduct_fr", "thigh_fr",
// "shank_fr" -> "fr"), separators trimmed.
std::string CommonSuffixName(const std::vector<std::string>& names) {
  std::vector<std::string> reversed;
  for (const std::string& n : names) reversed.emplace_back(n.rbegin(), n.rend());
  std::string suffix = CommonPrefixName(reversed);
  std::reverse(suffix.begin(), suffix.end());
  while (!suffix.empty() && (suffix.front() == '_' || suffix.front() == '-')) suffix.erase(suffix.begin());
  return suffix;
}

struct Chain {
  std::vector<urdf::JointConstSharedPtr> joints;  // body to foot
  std::vector<std::string> links;                 // below the body, body to foot
  std::vector<int> movable;                       // indices into joints of the movable ones
};

Chain ChainTo(const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& body,
              const urdf::LinkConstSharedPtr& foot, const std::string& path) {
  Chain chain;
  for (urdf::LinkConstSharedPtr link = foot; link && link != body && link->parent_joint;
       link = model.getLink(link->parent_joint->parent_link_name)) {
    if (static_cast<int>(chain.joints.size()) >= kMaxChainJoints) {
      throw InputError(path + ": the chain from the body to link '" + foot->name + "' has more than " +
                       std::to_string(kMaxChainJoints) + " joints (mfp reads at most " +
                       std::to_string(kMaxChainJoints) + " per leg)");
    }
    chain.joints.push_back(link->parent_joint);
    chain.links.push_back(link->name);
  }
  std::reverse(chain.joints.begin(), chain.joints.end());
  std::reverse(chain.links.begin(), chain.links.end());
  for (size_t i = 0; i < chain.joints.size(); ++i) {
    if (chain.joints[i]->type != urdf::Joint::FIXED) chain.movable.push_back(static_cast<int>(i));
  }
  return chain;
}

const urdf::Sphere* FootSphere(const urdf::Link& link, Eigen::Vector3d* centre) {
  for (const auto& collision : link.collision_array) {
    if (collision && collision->geometry && collision->geometry->type == urdf::Geometry::SPHERE) {
      const auto& p = collision->origin.position;
      *centre = Eigen::Vector3d(p.x, p.y, p.z);
      return static_cast<const urdf::Sphere*>(collision->geometry.get());
    }
  }
  return nullptr;
}

bool FootLikeName(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* word : {"foot", "feet", "toe", "tip"}) {
    if (name.find(word) != std::string::npos) return true;
  }
  return false;
}

LegChain MakeLeg(const urdf::Link& foot, const Chain& chain, const std::string& path,
                 std::vector<std::string>* notes) {
  LegChain leg;
  leg.foot_link = foot.name;
  for (const auto& joint : chain.joints) leg.joints.push_back(ToJointModel(*joint, path, notes));
  Eigen::Vector3d centre;
  if (const urdf::Sphere* sphere = FootSphere(foot, &centre)) {
    leg.p_footlink_foot_m = centre;
    leg.foot_sphere_radius_m = sphere->radius;
  }
  leg.name = CommonPrefixName(chain.links);
  if (leg.name.empty()) leg.name = CommonSuffixName(chain.links);
  return leg;
}

// Distance of the foot point from the chain's first movable joint at zero joint positions.
double ReachAtZero(const LegChain& leg) {
  if (leg.num_dof() == 0) return 0.0;
  return (FootPosition(leg, Eigen::VectorXd::Zero(leg.num_dof())) - HipPosition(leg)).norm();
}

// A leg found, with the document order of its first movable joint.
using OrderedLegs = std::vector<std::pair<int, LegChain>>;
using JointOrder = std::map<std::string, int>;

int FirstMovableOrder(const Chain& chain, const JointOrder& joint_order) {
  if (chain.movable.empty()) return 0;
  const auto it = joint_order.find(chain.joints[chain.movable.front()]->name);
  return it == joint_order.end() ? 0 : it->second;
}

urdf::ModelInterfaceSharedPtr ParseWithUrdfdom(const std::string& xml, const std::string& path) {
  urdf::ModelInterfaceSharedPtr model;
  std::string parser_messages;
  {
    CaptureConsole capture;
    model = urdf::parseURDF(xml);
    parser_messages = capture.messages();
  }
  if (!model) {
    throw InputError(path + ": not a valid URDF" + (parser_messages.empty() ? "" : ": " + parser_messages));
  }
  return model;
}

// The legs to the foot links the caller named, each with its own movable joints.
OrderedLegs LegsOfNamedFeet(const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& body,
                            const std::vector<std::string>& foot_links, const JointOrder& joint_order,
                            const std::string& path, std::vector<std::string>* notes) {
  if (static_cast<int>(foot_links.size()) > kMaxLegs) {
    throw InputError(path + ": " + std::to_string(foot_links.size()) + " foot links named; mfp plans for at most " +
                     std::to_string(kMaxLegs) + " legs");
  }
  OrderedLegs ordered;
  std::map<std::string, std::string> leg_of_joint;  // movable joint -> foot link using it
  for (const std::string& name : foot_links) {
    urdf::LinkConstSharedPtr link = model.getLink(name);
    if (!link) throw InputError(path + ": foot link '" + name + "' is not a link of the URDF");
    if (link == model.getRoot()) throw InputError(path + ": foot link '" + name + "' is the root link");
    const Chain chain = ChainTo(model, body, link, path);
    if (chain.movable.empty()) {
      throw InputError(path + ": foot link '" + name +
                       "' hangs from the root by fixed joints only (a leg needs a movable joint)");
    }
    for (int i : chain.movable) {
      const std::string& joint = chain.joints[i]->name;
      const auto [it, inserted] = leg_of_joint.emplace(joint, name);
      if (!inserted) {
        throw InputError(path + ": foot links '" + it->second + "' and '" + name + "' share the joint '" + joint +
                         "'; each leg needs its own joints");
      }
    }
    ordered.emplace_back(FirstMovableOrder(chain, joint_order), MakeLeg(*link, chain, path, notes));
  }
  return ordered;
}

using Leaf = std::pair<urdf::LinkConstSharedPtr, Chain>;

// Leaves below the body that hang from it by a movable joint, each with its chain.
std::vector<Leaf> LeafChains(const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& body,
                             const std::string& path) {
  std::vector<Leaf> leaves;
  std::vector<urdf::LinkConstSharedPtr> stack = {body};
  while (!stack.empty()) {
    const urdf::LinkConstSharedPtr link = stack.back();
    stack.pop_back();
    if (link->child_links.empty() && link != body) {
      Chain chain = ChainTo(model, body, link, path);
      if (!chain.movable.empty()) leaves.emplace_back(link, std::move(chain));
      continue;  // hanging off the body by fixed joints only: a sensor or cover
    }
    for (const auto& child : link->child_links) stack.push_back(child);
  }
  return leaves;
}

// Leaves that share a leg's first movable joint are one leg: the groups of leaf indices,
// in the order they are first met.
std::vector<std::vector<size_t>> GroupLeavesByLeg(const std::vector<Leaf>& leaves) {
  // A leaf whose last movable joint is not the last of another leaf hangs partway along
  // a leg by fixed joints (a rotor, a cover, a sensor): not a foot.
  std::set<std::string> inner;
  for (const auto& [leaf, chain] : leaves) {
    for (size_t i = 0; i + 1 < chain.movable.size(); ++i) inner.insert(chain.joints[chain.movable[i]]->name);
  }
  std::map<std::string, size_t> group_of;
  std::vector<std::vector<size_t>> groups;
  for (size_t i = 0; i < leaves.size(); ++i) {
    const Chain& chain = leaves[i].second;
    if (inner.count(chain.joints[chain.movable.back()]->name)) continue;
    const std::string key = chain.joints[chain.movable.front()]->name;
    const auto [it, inserted] = group_of.emplace(key, groups.size());
    if (inserted) groups.emplace_back();
    groups[it->second].push_back(i);
  }
  return groups;
}

// Rank of a foot candidate: a collision sphere, then a foot-like name, then more movable
// joints, then the foot point farthest from the hip at zero joint positions.
using FootRank = std::tuple<bool, bool, size_t, double>;

size_t BestFootOfGroup(const std::vector<Leaf>& leaves, const std::vector<size_t>& group,
                       const std::string& path, FootRank* best_rank) {
  size_t best = group.front();
  *best_rank = FootRank{false, false, 0, -1.0};
  for (size_t i : group) {
    const auto& [leaf, chain] = leaves[i];
    Eigen::Vector3d centre;
    const LegChain trial = MakeLeg(*leaf, chain, path, nullptr);
    const FootRank rank{FootSphere(*leaf, &centre) != nullptr, FootLikeName(leaf->name), chain.movable.size(),
                        ReachAtZero(trial)};
    if (rank > *best_rank) {
      *best_rank = rank;
      best = i;
    }
  }
  return best;
}

std::string ChosenFootNote(const std::vector<Leaf>& leaves, const std::vector<size_t>& group, size_t best,
                           const FootRank& rank) {
  std::string others;
  for (size_t i : group) {
    if (i != best) others += (others.empty() ? "'" : ", '") + leaves[i].first->name + "'";
  }
  return "foot link '" + leaves[best].first->name + "' chosen over " + others + " (same leg joints): " +
         (std::get<0>(rank) ? "collision sphere" : std::get<1>(rank) ? "foot-like name" : "farthest along the chain");
}

[[noreturn]] void ThrowNoLegs(const std::string& path, const urdf::ModelInterface& model,
                              const urdf::LinkConstSharedPtr& body, const std::vector<std::string>& one_joint) {
  if (!one_joint.empty()) {
    std::string list;
    for (const std::string& s : one_joint) list += (list.empty() ? "" : ", ") + s;
    throw InputError(path + ": no legs found: every chain from the body '" + body->name +
                     "' has a single movable joint (" + list +
                     "); a leg needs at least two, so rotating C-legs and wheels are not supported");
  }
  throw InputError(path + ": no legs found (no chain from the root link '" + model.getRoot()->name +
                   "' to a leaf link has a movable joint)");
}

// The legs found below the body: per group of leaves on the same leg joints, the best
// foot, when its chain has at least two movable joints.
OrderedLegs LegsOfLeaves(const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& body,
                         const JointOrder& joint_order, const std::string& path, std::vector<std::string>* notes) {
  const std::vector<Leaf> leaves = LeafChains(model, body, path);
  OrderedLegs ordered;
  std::vector<std::string> one_joint;
  int legs_found = 0;
  for (const std::vector<size_t>& group : GroupLeavesByLeg(leaves)) {
    FootRank rank;
    const size_t best = BestFootOfGroup(leaves, group, path, &rank);
    const auto& [leaf, chain] = leaves[best];
    if (chain.movable.size() < 2) {
      one_joint.push_back(leaf->name + " (joint '" + chain.joints[chain.movable.front()]->name + "')");
      continue;
    }
    if (++legs_found > kMaxLegs) {
      throw InputError(path + ": more than " + std::to_string(kMaxLegs) + " legs found; mfp plans for at most " +
                       std::to_string(kMaxLegs) + " legs");
    }
    if (group.size() > 1) notes->push_back(ChosenFootNote(leaves, group, best, rank));
    ordered.emplace_back(FirstMovableOrder(chain, joint_order), MakeLeg(*leaf, chain, path, notes));
  }
  if (ordered.empty()) ThrowNoLegs(path, model, body, one_joint);
  return ordered;
}

// Legs in document order, each named by its chain's links, or by its foot link where
// that name is empty or shared.
void OrderAndNameLegs(OrderedLegs* ordered) {
  std::stable_sort(ordered->begin(), ordered->end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::map<std::string, int> name_count;
  for (const auto& [order, leg] : *ordered) ++name_count[leg.name];
  for (auto& [order, leg] : *ordered) {
    if (leg.name.empty() || name_count[leg.name] > 1) leg.name = leg.foot_link;
  }
}

// The foot point must move with the last joint, else the URDF holds no foot (the lower
// leg is only in a mesh and the leaf link's origin is the knee).
void CheckFootMovesWithLastJoint(const LegChain& leg, const std::string& path) {
  const JointModel* last = nullptr;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity(), T_last = T;
  for (const JointModel& j : leg.joints) {
    T = T * j.T_parent_joint;
    if (j.movable()) {
      last = &j;
      T_last = T;
    }
  }
  const Eigen::Vector3d foot = FootPosition(leg, Eigen::VectorXd::Zero(leg.num_dof()));
  const Eigen::Vector3d axis = T_last.linear() * last->axis;
  const Eigen::Vector3d r = foot - T_last.translation();
  if (last->type == JointModel::Type::kRevolute && (r - r.dot(axis) * axis).norm() < 1e-6) {
    throw InputError(path + ": the URDF holds no foot for leg '" + leg.name + "': the foot link '" + leg.foot_link +
                     "' has its origin on the axis of the leg's last joint '" + last->name +
                     "' and no collision sphere (the lower leg is probably only a mesh); give the foot's "
                     "position in that link in a robot YAML: foot_offset: [x, y, z] (m)");
  }
}

// Refuses a leg with too many joints; sets or checks its foot point.
void SettleFoot(const std::optional<Eigen::Vector3d>& foot_offset_m, const std::string& path, LegChain* leg) {
  if (leg->num_dof() > kMaxLegDof) {
    throw InputError(path + ": leg to '" + leg->foot_link + "' has " + std::to_string(leg->num_dof()) +
                     " movable joints; mfp reads at most " + std::to_string(kMaxLegDof) + " per leg");
  }
  if (foot_offset_m) {
    leg->p_footlink_foot_m = *foot_offset_m;
  } else if (leg->foot_sphere_radius_m == 0.0) {
    CheckFootMovesWithLastJoint(*leg, path);
  }
}

}  // namespace

RobotDescription ReadUrdfRobot(const std::string& path, const std::vector<std::string>& foot_links,
                               const std::optional<Eigen::Vector3d>& foot_offset_m) {
  RobotDescription robot;
  const CheckedUrdfXml checked = ReadCheckedUrdfXml(path, &robot.notes);
  const urdf::ModelInterfaceSharedPtr model = ParseWithUrdfdom(checked.xml, path);
  robot.name = model->getName();
  robot.source = path;
  const urdf::LinkConstSharedPtr root = model->getRoot();
  if (!root) throw InputError(path + ": URDF has no root link");
  const urdf::LinkConstSharedPtr body = foot_links.empty() ? BodyLink(root, &robot.notes) : root;
  robot.root_link = body->name;
  ReadBodyBox(*body, &robot);
  OrderedLegs ordered = foot_links.empty()
                            ? LegsOfLeaves(*model, body, checked.joint_order, path, &robot.notes)
                            : LegsOfNamedFeet(*model, body, foot_links, checked.joint_order, path, &robot.notes);
  OrderAndNameLegs(&ordered);
  for (auto& [order, leg] : ordered) SettleFoot(foot_offset_m, path, &leg);
  for (auto& [order, leg] : ordered) robot.legs.push_back(leg);
  return robot;
}

}  // namespace mfp
