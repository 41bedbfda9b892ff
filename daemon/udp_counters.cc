#include "daemon/udp_counters.h"

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mfp {

int64_t ReadUdpReceiveErrors() {
  // Two "Udp:" lines: the field names, then the values.
  std::ifstream in("/proc/net/snmp");
  std::string line;
  std::vector<std::string> names;
  while (std::getline(in, line)) {
    if (line.rfind("Udp: ", 0) != 0) continue;
    std::istringstream fields(line.substr(5));
    std::vector<std::string> words;
    for (std::string w; fields >> w;) words.push_back(w);
    if (names.empty()) {
      names = words;
      continue;
    }
    for (size_t i = 0; i < names.size() && i < words.size(); ++i) {
      if (names[i] == "RcvbufErrors") return std::stoll(words[i]);
    }
    return -1;
  }
  return -1;
}

int64_t ReadRmemMax() {
  std::ifstream in("/proc/sys/net/core/rmem_max");
  int64_t bytes = -1;
  if (!(in >> bytes)) return -1;
  return bytes;
}

}  // namespace mfp
