#include "io/internal/npy_array.h"

#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "base/check.h"

namespace mfp {
namespace {

constexpr size_t kMaxHeaderBytes = 65536;
constexpr char kMagic[] = "\x93NUMPY";
constexpr size_t kMagicBytes = 6;

uint32_t LittleEndian(const uint8_t* p, int bytes) {
  uint32_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

// The value of `key` in the header dictionary, up to the next top-level ',' or '}'
// (a tuple's commas are inside its parentheses).
std::string HeaderValue(const std::string& header, const std::string& key, const std::string& what) {
  const std::string quoted[2] = {"'" + key + "'", "\"" + key + "\""};
  size_t at = std::string::npos;
  for (const std::string& q : quoted) {
    at = header.find(q);
    if (at != std::string::npos) {
      at += q.size();
      break;
    }
  }
  if (at == std::string::npos) throw InputError(what + ": the .npy header has no '" + key + "' field");
  at = header.find(':', at);
  if (at == std::string::npos) throw InputError(what + ": the .npy header's '" + key + "' has no value");
  ++at;
  int depth = 0;
  size_t end = at;
  for (; end < header.size(); ++end) {
    const char ch = header[end];
    if (ch == '(') ++depth;
    if (ch == ')') --depth;
    if (depth == 0 && (ch == ',' || ch == '}')) break;
  }
  const std::string raw = header.substr(at, end - at);
  const size_t b = raw.find_first_not_of(" \t'\""), e = raw.find_last_not_of(" \t'\"");
  return b == std::string::npos ? std::string() : raw.substr(b, e - b + 1);
}

std::vector<size_t> ParseShape(const std::string& text, const std::string& what) {
  if (text.size() < 2 || text.front() != '(' || text.back() != ')') {
    throw InputError(what + ": the .npy shape '" + text + "' is not a tuple");
  }
  std::vector<size_t> dims;
  std::stringstream in(text.substr(1, text.size() - 2));
  std::string part;
  while (std::getline(in, part, ',')) {
    const size_t b = part.find_first_not_of(" \t");
    if (b == std::string::npos) continue;  // the trailing comma of (n,)
    const std::string digits = part.substr(b, part.find_last_not_of(" \tL") - b + 1);
    if (digits.empty() || digits.size() > 12 || digits.find_first_not_of("0123456789") != std::string::npos) {
      throw InputError(what + ": the .npy shape '" + text + "' is not a tuple of sizes");
    }
    dims.push_back(static_cast<size_t>(std::stoull(digits)));
  }
  return dims;
}

template <typename T>
void CopyValues(const uint8_t* data, size_t count, std::vector<float>* out) {
  for (size_t k = 0; k < count; ++k) {
    T v;
    std::memcpy(&v, data + k * sizeof(T), sizeof(T));
    (*out)[k] = static_cast<float>(v);
  }
}

}  // namespace

NpyArray ParseNpy(const std::vector<uint8_t>& bytes, const std::string& what, size_t max_cells) {
  static_assert(std::numeric_limits<float>::is_iec559 && std::numeric_limits<double>::is_iec559,
                ".npy floats are IEEE 754");
  if (bytes.size() < kMagicBytes + 4 || std::memcmp(bytes.data(), kMagic, kMagicBytes) != 0) {
    throw InputError(what + ": not a .npy file (it does not start with the numpy magic bytes)");
  }
  const int major = bytes[6];
  if (major < 1 || major > 3) {
    throw InputError(what + ": .npy format version " + std::to_string(major) + " (1 to 3 are read)");
  }
  const int len_bytes = major == 1 ? 2 : 4;
  const size_t header_start = 8 + static_cast<size_t>(len_bytes);
  if (bytes.size() < header_start) throw InputError(what + ": the .npy header is cut short");
  const size_t header_len = LittleEndian(bytes.data() + 8, len_bytes);
  if (header_len > kMaxHeaderBytes || header_start + header_len > bytes.size()) {
    throw InputError(what + ": the .npy header length " + std::to_string(header_len) +
                     " is larger than the file or than 64 KiB");
  }
  const std::string header(reinterpret_cast<const char*>(bytes.data() + header_start), header_len);
  const std::string descr = HeaderValue(header, "descr", what);
  const std::string order = HeaderValue(header, "fortran_order", what);
  const std::vector<size_t> shape = ParseShape(HeaderValue(header, "shape", what), what);
  size_t item = 0;
  if (descr == "<f4") item = 4;
  if (descr == "<f8") item = 8;
  if (item == 0) {
    throw InputError(what + ": the .npy dtype is '" + descr +
                     "'; give float32 or float64 heights (dtype '<f4' or '<f8': arr.astype(np.float32))");
  }
  if (order != "False" && order != "True") {
    throw InputError(what + ": the .npy fortran_order is '" + order + "', not True or False");
  }
  if (shape.size() != 2) {
    throw InputError(what + ": the .npy array has " + std::to_string(shape.size()) +
                     " dimensions; a height map is 2-D (heights[i, j], i along x, j along y)");
  }
  if (shape[0] == 0 || shape[1] == 0 || shape[0] > max_cells || shape[1] > max_cells / shape[0]) {
    throw InputError(what + ": the .npy array is " + std::to_string(shape[0]) + " x " +
                     std::to_string(shape[1]) + "; it must have between 1 and " +
                     std::to_string(max_cells) + " cells");
  }
  const size_t count = shape[0] * shape[1];
  const size_t data_start = header_start + header_len;
  if (bytes.size() - data_start != count * item) {
    throw InputError(what + ": the .npy data holds " + std::to_string(bytes.size() - data_start) +
                     " bytes, but a " + std::to_string(shape[0]) + " x " + std::to_string(shape[1]) +
                     " array of '" + descr + "' needs " + std::to_string(count * item));
  }
  NpyArray out;
  out.rows = shape[0];
  out.cols = shape[1];
  std::vector<float> flat(count);
  if (item == 4) CopyValues<float>(bytes.data() + data_start, count, &flat);
  if (item == 8) CopyValues<double>(bytes.data() + data_start, count, &flat);
  if (order == "False") {
    out.values = std::move(flat);
  } else {  // Fortran order: the first index varies fastest.
    out.values.resize(count);
    for (size_t c = 0; c < out.cols; ++c) {
      for (size_t r = 0; r < out.rows; ++r) out.values[r * out.cols + c] = flat[c * out.rows + r];
    }
  }
  return out;
}

NpyArray ReadNpyFile(const std::string& path, size_t max_cells) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(path + ": cannot open the height map array (.npy)");
  const std::streamoff size = in.tellg();
  const double max_bytes = 8.0 * static_cast<double>(max_cells) + 16.0 + kMaxHeaderBytes;
  if (size < 0 || static_cast<double>(size) > max_bytes) {
    throw InputError(path + ": the .npy file has " + std::to_string(size) +
                     " bytes, more than a map of the largest size allowed (" +
                     std::to_string(max_cells) + " cells of float64)");
  }
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), size)) throw InputError(path + ": cannot read the file");
  return ParseNpy(bytes, path, max_cells);
}

std::vector<uint8_t> NpyBytes(const NpyArray& array) {
  MFP_CHECK(array.values.size() == array.rows * array.cols);
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(array.rows) +
                       ", " + std::to_string(array.cols) + "), }";
  // Magic, version, length and header padded to a multiple of 64 bytes, ending in '\n'.
  const size_t unpadded = kMagicBytes + 4 + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header.push_back('\n');
  std::vector<uint8_t> out(kMagic, kMagic + kMagicBytes);
  out.push_back(1);
  out.push_back(0);
  out.push_back(static_cast<uint8_t>(header.size() & 0xff));
  out.push_back(static_cast<uint8_t>(header.size() >> 8));
  out.insert(out.end(), header.begin(), header.end());
  const size_t data = out.size();
  out.resize(data + 4 * array.values.size());
  std::memcpy(out.data() + data, array.values.data(), 4 * array.values.size());
  return out;
}

}  // namespace mfp
