#pragma once
// Magnitude checks on a URDF's numbers, before urdfdom parses them: a finite number can
// still be absurd (a collision origin at 1e308 m), and the reachable-footprint grid is
// sized from the lengths the URDF implies. Only TinyXML2 here, like urdf_reader.cc.
#include <string>

namespace tinyxml2 {
class XMLElement;
}

namespace mfp {

// Largest length a URDF may state [m]: positions (xyz of every origin and of the foot
// offset), sizes (radius, length, box size, mesh scale), the axis and a prismatic
// joint's limits. A kilometre is far beyond any legged robot, and keeps every derived
// extent (reach, footprint grid, workspace) finite with room to spare.
constexpr double kMaxUrdfLengthM = 1000.0;

// Throws InputError naming the file, line, element and attribute of the first number
// whose magnitude exceeds kMaxUrdfLengthM, among xyz, radius, length, size and scale
// attributes anywhere below `robot`, and lower/upper of a prismatic joint's <limit>.
// Angles (rpy, a revolute joint's limits) may be any finite number: the reader folds
// them into one turn. Non-numeric tokens are left to urdfdom.
void CheckUrdfMagnitudes(const tinyxml2::XMLElement* robot, const std::string& path);

}  // namespace mfp
