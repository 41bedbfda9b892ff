#pragma once
// File-name helpers shared by the readers that choose a format by a file's extension.
#include <string>

namespace mfp {

// The extension of the path's last component, without its dot and case kept ("" when
// the last component has no dot): "maps/a.b/room.BT" -> "BT".
std::string FileExtension(const std::string& path);
// FileExtension in lower case: "room.BT" -> "bt".
std::string LowerFileExtension(const std::string& path);
// The path without its extension and the dot: "maps/room.npy" -> "maps/room".
std::string WithoutFileExtension(const std::string& path);

}  // namespace mfp
