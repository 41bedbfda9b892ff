#include "planner/robot/urdf_reader.h"

#include <console_bridge/console.h>
#include <tinyxml2.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "planner/base/check.h"

namespace mfp {
namespace {

std::string ReadWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": no such file or not readable");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": could not be read");
  return text.str();
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

JointModel ToJointModel(const urdf::Joint& joint, const std::string& path) {
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

struct Chain {
  std::vector<urdf::JointConstSharedPtr> joints;  // root to foot
  std::vector<std::string> links;                 // below the root, root to foot
};

Chain ChainTo(const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& foot) {
  Chain chain;
  for (urdf::LinkConstSharedPtr link = foot; link && link->parent_joint;
       link = model.getLink(link->parent_joint->parent_link_name)) {
    chain.joints.push_back(link->parent_joint);
    chain.links.push_back(link->name);
  }
  std::reverse(chain.joints.begin(), chain.joints.end());
  std::reverse(chain.links.begin(), chain.links.end());
  return chain;
}

bool HasMovableJoint(const Chain& chain) {
  for (const auto& j : chain.joints) {
    if (j->type != urdf::Joint::FIXED) return true;
  }
  return false;
}

}  // namespace

RobotDescription ReadUrdfRobot(const std::string& path,
                               const std::vector<std::string>& foot_links) {
  const std::string xml = ReadWholeFile(path);
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    std::ostringstream msg;
    msg << path << ": malformed XML at line " << doc.ErrorLineNum() << ": " << doc.ErrorStr();
    throw InputError(msg.str());
  }
  const tinyxml2::XMLElement* robot_xml = doc.FirstChildElement("robot");
  if (robot_xml == nullptr) throw InputError(path + ": not a URDF (no <robot> element)");
  CheckFiniteNumbers(robot_xml, path);
  const std::map<std::string, int> joint_order = JointOrder(robot_xml);

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
  RobotDescription robot;
  robot.name = model->getName();
  robot.source = path;
  const urdf::LinkConstSharedPtr root = model->getRoot();
  if (!root) throw InputError(path + ": URDF has no root link");
  robot.root_link = root->name;

  std::vector<urdf::LinkConstSharedPtr> feet;
  if (!foot_links.empty()) {
    for (const std::string& name : foot_links) {
      urdf::LinkConstSharedPtr link = model->getLink(name);
      if (!link) throw InputError(path + ": foot link '" + name + "' is not a link of the URDF");
      if (link == root) throw InputError(path + ": foot link '" + name + "' is the root link");
      feet.push_back(link);
    }
  } else {
    std::vector<urdf::LinkSharedPtr> links;
    model->getLinks(links);
    for (const auto& link : links) {
      if (link->child_links.empty() && link != root) feet.push_back(link);
    }
  }

  std::map<std::string, std::string> leg_of_joint;  // movable joint -> foot link using it
  std::vector<std::pair<int, LegChain>> ordered;
  for (const auto& foot : feet) {
    const Chain chain = ChainTo(*model, foot);
    if (!HasMovableJoint(chain)) {
      if (!foot_links.empty()) {
        throw InputError(path + ": foot link '" + foot->name +
                         "' hangs from the root by fixed joints only (a leg needs a movable joint)");
      }
      continue;  // a sensor or cover fixed to the body, not a leg
    }
    LegChain leg;
    leg.foot_link = foot->name;
    int first_movable = -1;
    for (const auto& joint : chain.joints) {
      leg.joints.push_back(ToJointModel(*joint, path));
      if (joint->type == urdf::Joint::FIXED) continue;
      if (first_movable < 0) {
        const auto it = joint_order.find(joint->name);
        first_movable = it == joint_order.end() ? 0 : it->second;
      }
      const auto [it, inserted] = leg_of_joint.emplace(joint->name, foot->name);
      if (!inserted) {
        throw InputError(path + ": links '" + it->second + "' and '" + foot->name +
                         "' share the joint '" + joint->name +
                         "'; name the foot links in the robot YAML (feet: [...])");
      }
    }
    for (const auto& collision : foot->collision_array) {
      if (collision && collision->geometry &&
          collision->geometry->type == urdf::Geometry::SPHERE) {
        const auto& p = collision->origin.position;
        leg.p_footlink_foot_m = Eigen::Vector3d(p.x, p.y, p.z);
        leg.foot_sphere_radius_m =
            static_cast<const urdf::Sphere&>(*collision->geometry).radius;
        break;
      }
    }
    leg.name = CommonPrefixName(chain.links);
    ordered.emplace_back(first_movable, leg);
  }
  if (ordered.empty()) {
    throw InputError(path + ": no legs found (no chain from the root link '" + root->name +
                     "' to a leaf link has a movable joint)");
  }
  std::stable_sort(ordered.begin(), ordered.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::map<std::string, int> name_count;
  for (const auto& [order, leg] : ordered) ++name_count[leg.name];
  for (auto& [order, leg] : ordered) {
    if (leg.name.empty() || name_count[leg.name] > 1) leg.name = leg.foot_link;
    robot.legs.push_back(leg);
  }
  return robot;
}

}  // namespace mfp
