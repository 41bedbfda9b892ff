#pragma once
// The URDF's XML read and checked before urdfdom sees it: the first stage of
// ReadUrdfRobot, and the only file that includes TinyXML2 headers.
#include <map>
#include <string>
#include <vector>

namespace mfp {

// Limits of the URDF path (docs/robot_derivation.md): beyond them a description is
// refused with a message instead of exhausting time or memory.
inline constexpr int kMaxLinks = 10000;      // links in the file
inline constexpr int kMaxLegs = 16;          // legs found (or named)
inline constexpr int kMaxLegDof = 12;        // movable joints in one leg
inline constexpr int kMaxChainJoints = 64;   // joints (fixed included) from the body to a foot

// The XML text for urdfdom and what was learnt from the raw XML on the way.
struct CheckedUrdfXml {
  std::string xml;                        // pruned, re-printed
  std::map<std::string, int> joint_order;  // document order of the joints by name
};

// Reads the URDF at path and refuses malformed XML, a file with no <robot>, numbers that
// are not finite and a joint graph that is not a tree; links in no joint are removed and
// noted in notes.
CheckedUrdfXml ReadCheckedUrdfXml(const std::string& path, std::vector<std::string>* notes);

}  // namespace mfp
