#include "planner/robot/internal/urdf_xml_checks.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

#include "base/bounded_file.h"
#include "base/check.h"
#include "planner/robot/internal/urdf_numbers.h"

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

}  // namespace

CheckedUrdfXml ReadCheckedUrdfXml(const std::string& path, std::vector<std::string>* notes) {
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
  CheckAndPruneJointGraph(robot_xml, path, notes);
  CheckedUrdfXml checked;
  checked.joint_order = JointOrder(robot_xml);
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  checked.xml = printer.CStr();
  return checked;
}

}  // namespace mfp
