#include "planner/robot/internal/urdf_numbers.h"

#include <tinyxml2.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "base/check.h"

namespace mfp {
namespace {

bool IsLengthAttribute(const char* name) {
  for (const char* length : {"xyz", "radius", "length", "size", "scale"}) {
    if (std::strcmp(name, length) == 0) return true;
  }
  return false;
}

// lower / upper of <joint type="prismatic"><limit>: metres, not angles.
bool IsPrismaticLimit(const tinyxml2::XMLElement& element, const char* attribute) {
  if (std::strcmp(element.Name(), "limit") != 0) return false;
  if (std::strcmp(attribute, "lower") != 0 && std::strcmp(attribute, "upper") != 0) return false;
  const tinyxml2::XMLElement* joint = element.Parent() ? element.Parent()->ToElement() : nullptr;
  const char* type = joint ? joint->Attribute("type") : nullptr;
  return type != nullptr && std::strcmp(type, "prismatic") == 0;
}

void CheckAttribute(const tinyxml2::XMLElement& element, const tinyxml2::XMLAttribute& a,
                    const std::string& path) {
  std::istringstream tokens(a.Value());
  std::string token;
  while (tokens >> token) {
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (end == nullptr || *end != '\0' || std::abs(value) <= kMaxUrdfLengthM) continue;
    std::ostringstream msg;
    msg << path << ": line " << element.GetLineNum() << ": <" << element.Name() << "> attribute '"
        << a.Name() << "' = '" << token << "' is beyond +-" << kMaxUrdfLengthM
        << " m; a robot's lengths are metres (check the units and the number)";
    throw InputError(msg.str());
  }
}

void CheckElements(const tinyxml2::XMLElement* element, const std::string& path, int depth) {
  // TinyXML2 itself caps nesting; the depth guard keeps this walk bounded regardless.
  if (depth > 1000) return;
  for (; element != nullptr; element = element->NextSiblingElement()) {
    for (const tinyxml2::XMLAttribute* a = element->FirstAttribute(); a != nullptr; a = a->Next()) {
      if (IsLengthAttribute(a->Name()) || IsPrismaticLimit(*element, a->Name())) {
        CheckAttribute(*element, *a, path);
      }
    }
    CheckElements(element->FirstChildElement(), path, depth + 1);
  }
}

}  // namespace

void CheckUrdfMagnitudes(const tinyxml2::XMLElement* robot, const std::string& path) {
  if (robot != nullptr) CheckElements(robot->FirstChildElement(), path, 0);
}

}  // namespace mfp
