#include "planner/robot/urdf_reader.h"

#include <console_bridge/console.h>
#include <tinyxml2.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "planner/base/bounded_file.h"
#include "planner/base/check.h"
#include "planner/robot/urdf_numbers.h"

namespace mfp {
namespace {

// Only a regular file, at most kMaxTextInputBytes (never /dev/zero or a FIFO).
std::string ReadWholeFile(const std::string& path) {
  return ReadBoundedRegularFile(path, kMaxTextInputBytes, "URDF");
}

// Attributes that hold numbers in URDF; each is checked for NaN and infinity, which
// urdfdom parses without complaint.
bool IsNumericAttribute(const std::string& name) {
  static const std::set<std::string> kNumeric = {
      "xyz",   "rpy",    "lower",  "upper", "effort", "velocity", "radius", "length",
      "size",  "value",  "scale",  "ixx",   "ixy",    "ixz",      "iyy",    "iyz",
      "izz",   "damping", "friction", "soft_lower_limit", "soft_upper_limit",
      "k_position", "k_velocity", "multiplier", "offset", "rising", "falling"};
  return kNumeric.count(name) > 0;
}

void CheckFiniteNumbers(const tinyxml2::XMLElement* element, const std::string& path) {
  for (; element != nullptr; element = element->NextSiblingElement()) {
    for (const tinyxml2::XMLAttribute* a = element->FirstAttribute(); a != nullptr;
         a = a->Next()) {
      if (!IsNumericAttribute(a->Name())) continue;
      std::istringstream tokens(a->Value());
      std::string token;
      while (tokens >> token) {
        char* end = nullptr;
        errno = 0;
        const double value = std::strtod(token.c_str(), &end);
        const bool whole = end != nullptr && *end == '\0';
        if (whole && !std::isfinite(value)) {
          std::ostringstream msg;
          msg << path << ": line " << element->GetLineNum() << ": <" << element->Name()
              << "> attribute '" << a->Name() << "' = '" << a->Value()
              << "' is not a finite number";
          throw InputError(msg.str());
        }
      }
    }
    CheckFiniteNumbers(element->FirstChildElement(), path);
  }
}

// Document order of the joints, for a leg order that follows the file.
std::map<std::string, int> JointOrder(const tinyxml2::XMLElement* robot) {
  std::map<std::string, int> order;
  int index = 0;
  for (const tinyxml2::XMLElement* j = robot->FirstChildElement("joint"); j != nullptr;
       j = j->NextSiblingElement("joint")) {
    const char* name = j->Attribute("name");
    if (name != nullptr) order.emplace(name, index++);
  }
  return order;
}

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

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  T.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y,
                                  pose.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  return T;
}

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

// Limits of the URDF path (docs/robot_derivation.md): beyond them a description is
// refused with a message instead of exhausting time or memory.
constexpr int kMaxLinks = 10000;      // links in the file
constexpr int kMaxLegs = 16;          // legs found (or named)
constexpr int kMaxLegDof = 12;        // movable joints in one leg
constexpr int kMaxChainJoints = 64;   // joints (fixed included) from the body to a foot

// Checks the joint graph of the raw XML before urdfdom sees it: too many links, a joint
// whose parent is its child, joints that form a loop (urdfdom accepts a loop that is not
// connected to the root, and walking up from it never ends). Removes links that appear
// in no joint (urdfdom takes each for a second root), noting them.
void CheckAndPruneJointGraph(tinyxml2::XMLElement* robot_xml, const std::string& path,
                             std::vector<std::string>* notes) {
  std::map<std::string, std::pair<std::string, std::string>> parent_of;  // child -> (parent, joint)
  std::set<std::string> in_joint;
  int links = 0;
  for (const tinyxml2::XMLElement* l = robot_xml->FirstChildElement("link"); l != nullptr;
       l = l->NextSiblingElement("link")) {
    if (++links > kMaxLinks) {
      throw InputError(path + ": more than " + std::to_string(kMaxLinks) +
                       " links (mfp reads at most " + std::to_string(kMaxLinks) + ")");
    }
  }
  for (const tinyxml2::XMLElement* j = robot_xml->FirstChildElement("joint"); j != nullptr;
       j = j->NextSiblingElement("joint")) {
    const tinyxml2::XMLElement* parent = j->FirstChildElement("parent");
    const tinyxml2::XMLElement* child = j->FirstChildElement("child");
    const char* name = j->Attribute("name");
    const char* p = parent ? parent->Attribute("link") : nullptr;
    const char* c = child ? child->Attribute("link") : nullptr;
    if (name == nullptr || p == nullptr || c == nullptr) continue;  // urdfdom reports these
    const std::string where = path + ": line " + std::to_string(j->GetLineNum()) + ": joint '" + name + "'";
    if (std::string(p) == c) throw InputError(where + ": link '" + p + "' is its own parent");
    in_joint.insert(p);
    in_joint.insert(c);
    parent_of.emplace(c, std::make_pair(std::string(p), std::string(name)));
  }
  // Walk up from every link; a walk that meets itself is a loop. Each link is finished once.
  std::map<std::string, int> state;  // 1 on the current walk, 2 finished
  for (const auto& [start, unused] : parent_of) {
    std::vector<std::string> walk;
    std::string link = start;
    while (true) {
      int& s = state[link];
      if (s == 2) break;
      if (s == 1) {
        std::string cycle;
        for (auto it = std::find(walk.begin(), walk.end(), link); it != walk.end(); ++it) {
          cycle += "'" + parent_of.at(*it).second + "' -> ";
        }
        throw InputError(path + ": the joints form a loop (" + cycle + "back to link '" + link +
                         "'); a URDF must be a tree");
      }
      s = 1;
      walk.push_back(link);
      const auto up = parent_of.find(link);
      if (up == parent_of.end()) break;
      link = up->second.first;
    }
    for (const std::string& l : walk) state[l] = 2;
  }
  if (in_joint.empty()) return;
  std::vector<tinyxml2::XMLElement*> orphans;
  for (tinyxml2::XMLElement* l = robot_xml->FirstChildElement("link"); l != nullptr;
       l = l->NextSiblingElement("link")) {
    const char* name = l->Attribute("name");
    if (name != nullptr && in_joint.count(name) == 0) orphans.push_back(l);
  }
  for (tinyxml2::XMLElement* l : orphans) {
    notes->push_back(std::string("link '") + l->Attribute("name") + "' is in no joint: ignored");
    robot_xml->DeleteChild(l);
  }
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

// Below a root that is only a frame (`world`, `base` with a floating or fixed joint to the
// body and nothing else) lies the body the legs hang from.
urdf::LinkConstSharedPtr BodyLink(const urdf::LinkConstSharedPtr& root, std::vector<std::string>* notes) {
  urdf::LinkConstSharedPtr body = root;
  for (int depth = 0; depth < kMaxLinks && body->child_joints.size() == 1; ++depth) {
    const urdf::JointSharedPtr& joint = body->child_joints.front();
    if (joint->type != urdf::Joint::FLOATING && joint->type != urdf::Joint::FIXED) break;
    if (body->child_links.size() != 1) break;
    notes->push_back("body: link '" + body->child_links.front()->name + "', below '" + body->name +
                     "' by the " + (joint->type == urdf::Joint::FLOATING ? "floating" : "fixed") +
                     " joint '" + joint->name + "'");
    body = body->child_links.front();
  }
  return body;
}

// Bounding box, in the link frame, of one primitive shape placed at `origin` [m]; empty
// for meshes (not read).
Eigen::AlignedBox3d ShapeBox(const urdf::Geometry& geometry, const urdf::Pose& origin) {
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const auto& d = static_cast<const urdf::Box&>(geometry).dim;
      half = 0.5 * Eigen::Vector3d(d.x, d.y, d.z);
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(geometry);
      half = Eigen::Vector3d(c.radius, c.radius, 0.5 * c.length);
      break;
    }
    case urdf::Geometry::SPHERE:
      half = Eigen::Vector3d::Constant(static_cast<const urdf::Sphere&>(geometry).radius);
      break;
    default:
      return Eigen::AlignedBox3d();
  }
  const Eigen::Isometry3d T = ToIsometry(origin);
  Eigen::AlignedBox3d box;
  const Eigen::AlignedBox3d local(-half, half);
  for (int corner = 0; corner < 8; ++corner) {
    box.extend(T * local.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
  }
  return box;
}

// The box of uniform density whose principal moments are the link's inertia (a box of
// sides a, b, c has Ixx = m (b^2 + c^2) / 12, ...), about the inertial origin; empty when
// the link has no mass or the moments fit no box.
Eigen::AlignedBox3d InertiaBox(const urdf::Inertial& inertial) {
  const double m = inertial.mass;
  if (!(m > 0.0)) return Eigen::AlignedBox3d();
  const double ixx = inertial.ixx, iyy = inertial.iyy, izz = inertial.izz;
  const Eigen::Vector3d squared = 6.0 / m * Eigen::Vector3d(iyy + izz - ixx, ixx + izz - iyy, ixx + iyy - izz);
  if (!(squared.minCoeff() > 0.0)) return Eigen::AlignedBox3d();
  const Eigen::Vector3d half = 0.5 * squared.cwiseSqrt();
  const Eigen::Isometry3d T = ToIsometry(inertial.origin);
  Eigen::AlignedBox3d box;
  const Eigen::AlignedBox3d local(-half, half);
  for (int corner = 0; corner < 8; ++corner) {
    box.extend(T * local.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
  }
  return box;
}

// The body link's extent (RobotDescription::body_box_m) and where it came from.
void ReadBodyBox(const urdf::Link& body, RobotDescription* robot) {
  Eigen::AlignedBox3d box;
  for (const auto& collision : body.collision_array) {
    if (collision && collision->geometry) box.extend(ShapeBox(*collision->geometry, collision->origin));
  }
  if (!box.isEmpty()) {
    robot->body_box_m = box;
    robot->body_box_source = "collision shapes of link '" + body.name + "'";
    return;
  }
  for (const auto& visual : body.visual_array) {
    if (visual && visual->geometry) box.extend(ShapeBox(*visual->geometry, visual->origin));
  }
  if (!box.isEmpty()) {
    robot->body_box_m = box;
    robot->body_box_source = "visual shapes of link '" + body.name + "'";
    return;
  }
  if (body.inertial) box = InertiaBox(*body.inertial);
  if (!box.isEmpty()) {
    robot->body_box_m = box;
    robot->body_box_source = "box of uniform density with the inertia of link '" + body.name + "'";
  }
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

}  // namespace

RobotDescription ReadUrdfRobot(const std::string& path, const std::vector<std::string>& foot_links,
                               const std::optional<Eigen::Vector3d>& foot_offset_m) {
  const std::string xml_in = ReadWholeFile(path);
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml_in.c_str(), xml_in.size()) != tinyxml2::XML_SUCCESS) {
    std::ostringstream msg;
    msg << path << ": malformed XML at line " << doc.ErrorLineNum() << ": " << doc.ErrorStr();
    throw InputError(msg.str());
  }
  tinyxml2::XMLElement* robot_xml = doc.FirstChildElement("robot");
  if (robot_xml == nullptr) throw InputError(path + ": not a URDF (no <robot> element)");
  CheckFiniteNumbers(robot_xml, path);
  CheckUrdfMagnitudes(robot_xml, path);
  RobotDescription robot;
  CheckAndPruneJointGraph(robot_xml, path, &robot.notes);
  const std::map<std::string, int> joint_order = JointOrder(robot_xml);
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  const std::string xml = printer.CStr();

  urdf::ModelInterfaceSharedPtr model;
  std::string parser_messages;
  {
    CaptureConsole capture;
    model = urdf::parseURDF(xml);
    parser_messages = capture.messages();
  }
  if (!model) {
    throw InputError(path + ": not a valid URDF" +
                     (parser_messages.empty() ? "" : ": " + parser_messages));
  }
  robot.name = model->getName();
  robot.source = path;
  const urdf::LinkConstSharedPtr root = model->getRoot();
  if (!root) throw InputError(path + ": URDF has no root link");
  const urdf::LinkConstSharedPtr body = foot_links.empty() ? BodyLink(root, &robot.notes) : root;
  robot.root_link = body->name;
  ReadBodyBox(*body, &robot);

  auto first_movable_order = [&](const Chain& chain) {
    if (chain.movable.empty()) return 0;
    const auto it = joint_order.find(chain.joints[chain.movable.front()]->name);
    return it == joint_order.end() ? 0 : it->second;
  };
  std::vector<std::pair<int, LegChain>> ordered;
  if (!foot_links.empty()) {
    if (static_cast<int>(foot_links.size()) > kMaxLegs) {
      throw InputError(path + ": " + std::to_string(foot_links.size()) + " foot links named; mfp plans for at most " +
                       std::to_string(kMaxLegs) + " legs");
    }
    std::map<std::string, std::string> leg_of_joint;  // movable joint -> foot link using it
    for (const std::string& name : foot_links) {
      urdf::LinkConstSharedPtr link = model->getLink(name);
      if (!link) throw InputError(path + ": foot link '" + name + "' is not a link of the URDF");
      if (link == root) throw InputError(path + ": foot link '" + name + "' is the root link");
      const Chain chain = ChainTo(*model, body, link, path);
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
      ordered.emplace_back(first_movable_order(chain), MakeLeg(*link, chain, path, &robot.notes));
    }
  } else {
    // Leaves below the body, each with its chain.
    std::vector<std::pair<urdf::LinkConstSharedPtr, Chain>> leaves;
    std::vector<urdf::LinkConstSharedPtr> stack = {body};
    while (!stack.empty()) {
      const urdf::LinkConstSharedPtr link = stack.back();
      stack.pop_back();
      if (link->child_links.empty() && link != body) {
        Chain chain = ChainTo(*model, body, link, path);
        if (!chain.movable.empty()) leaves.emplace_back(link, std::move(chain));
        continue;  // hanging off the body by fixed joints only: a sensor or cover
      }
      for (const auto& child : link->child_links) stack.push_back(child);
    }
    // A leaf whose last movable joint is not the last of another leaf hangs partway along
    // a leg by fixed joints (a rotor, a cover, a sensor): not a foot.
    std::set<std::string> inner;
    for (const auto& [leaf, chain] : leaves) {
      for (size_t i = 0; i + 1 < chain.movable.size(); ++i) inner.insert(chain.joints[chain.movable[i]]->name);
    }
    // Leaves that share a leg's first movable joint are one leg: keep the best foot.
    std::map<std::string, std::vector<size_t>> groups;
    std::vector<std::string> group_order;
    for (size_t i = 0; i < leaves.size(); ++i) {
      const Chain& chain = leaves[i].second;
      if (inner.count(chain.joints[chain.movable.back()]->name)) continue;
      const std::string key = chain.joints[chain.movable.front()]->name;
      if (groups[key].empty()) group_order.push_back(key);
      groups[key].push_back(i);
    }
    std::vector<std::string> one_joint;
    int legs_found = 0;
    for (const std::string& key : group_order) {
      const std::vector<size_t>& group = groups[key];
      // Rank: a collision sphere, then a foot-like name, then more movable joints, then
      // the foot point farthest from the hip at zero joint positions.
      size_t best = group.front();
      std::tuple<bool, bool, size_t, double> best_rank{false, false, 0, -1.0};
      for (size_t i : group) {
        const auto& [leaf, chain] = leaves[i];
        Eigen::Vector3d centre;
        const LegChain trial = MakeLeg(*leaf, chain, path, nullptr);
        const std::tuple<bool, bool, size_t, double> rank{FootSphere(*leaf, &centre) != nullptr,
                                                          FootLikeName(leaf->name), chain.movable.size(),
                                                          ReachAtZero(trial)};
        if (rank > best_rank) {
          best_rank = rank;
          best = i;
        }
      }
      const auto& [leaf, chain] = leaves[best];
      if (chain.movable.size() < 2) {
        one_joint.push_back(leaf->name + " (joint '" + chain.joints[chain.movable.front()]->name + "')");
        continue;
      }
      if (++legs_found > kMaxLegs) {
        throw InputError(path + ": more than " + std::to_string(kMaxLegs) + " legs found; mfp plans for at most " +
                         std::to_string(kMaxLegs) + " legs");
      }
      if (group.size() > 1) {
        std::string others;
        for (size_t i : group) {
          if (i != best) others += (others.empty() ? "'" : ", '") + leaves[i].first->name + "'";
        }
        robot.notes.push_back("foot link '" + leaf->name + "' chosen over " + others +
                              " (same leg joints): " +
                              (std::get<0>(best_rank) ? "collision sphere"
                               : std::get<1>(best_rank) ? "foot-like name"
                                                        : "farthest along the chain"));
      }
      ordered.emplace_back(first_movable_order(chain), MakeLeg(*leaf, chain, path, &robot.notes));
    }
    if (ordered.empty()) {
      if (!one_joint.empty()) {
        std::string list;
        for (const std::string& s : one_joint) list += (list.empty() ? "" : ", ") + s;
        throw InputError(path + ": no legs found: every chain from the body '" + body->name +
                         "' has a single movable joint (" + list +
                         "); a leg needs at least two, so rotating C-legs and wheels are not supported");
      }
      throw InputError(path + ": no legs found (no chain from the root link '" + root->name +
                       "' to a leaf link has a movable joint)");
    }
  }
  std::stable_sort(ordered.begin(), ordered.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::map<std::string, int> name_count;
  for (const auto& [order, leg] : ordered) ++name_count[leg.name];
  for (auto& [order, leg] : ordered) {
    if (leg.name.empty() || name_count[leg.name] > 1) leg.name = leg.foot_link;
  }
  for (auto& [order, leg] : ordered) {
    if (leg.num_dof() > kMaxLegDof) {
      throw InputError(path + ": leg to '" + leg.foot_link + "' has " + std::to_string(leg.num_dof()) +
                       " movable joints; mfp reads at most " + std::to_string(kMaxLegDof) + " per leg");
    }
    if (foot_offset_m) {
      leg.p_footlink_foot_m = *foot_offset_m;
    } else if (leg.foot_sphere_radius_m == 0.0) {
      // The foot point must move with the last joint, else the URDF holds no foot (the
      // lower leg is only in a mesh and the leaf link's origin is the knee).
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
  }
  for (auto& [order, leg] : ordered) robot.legs.push_back(leg);
  return robot;
}

}  // namespace mfp
