#include "io/file_paths.h"

#include <algorithm>
#include <cctype>

namespace mfp {

std::string FileExtension(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  return path.substr(dot + 1);
}

std::string LowerFileExtension(const std::string& path) {
  std::string ext = FileExtension(path);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string WithoutFileExtension(const std::string& path) {
  const std::string ext = FileExtension(path);
  if (ext.empty() && (path.empty() || path.back() != '.')) return path;
  return path.substr(0, path.size() - ext.size() - 1);
}

}  // namespace mfp
