#include "terrain/octomap/internal/octree_stream_check.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <sstream>

#include "base/check.h"

namespace mfp {
namespace {

constexpr char kBinaryHeader[] = "# Octomap OcTree binary file";
constexpr char kFullHeader[] = "# Octomap OcTree file";
constexpr int kTreeDepth = 16;         // OctoMap's OcTree has 16 levels below the root
constexpr size_t kMaxHeaderBytes = 4096;

class Reader {
 public:
  Reader(const uint8_t* data, size_t size, const std::string& what)
      : data_(data), size_(size), what_(what) {}

  [[noreturn]] void Fail(const std::string& problem) const {
    throw InputError(what_ + ": not a valid OctoMap file: " + problem);
  }
  size_t pos() const { return pos_; }
  const std::string& what() const { return what_; }
  bool AtEnd() const { return pos_ >= size_; }

  // The first line, as std::getline would read it.
  std::string Line() {
    std::string line;
    while (pos_ < size_ && data_[pos_] != '\n') {
      if (line.size() >= kMaxHeaderBytes) Fail("the first line is too long");
      line.push_back(static_cast<char>(data_[pos_++]));
    }
    if (pos_ < size_) ++pos_;
    return line;
  }
  // A whitespace-separated token, as `stream >> token` would read it ("" at the end).
  std::string Token() {
    while (pos_ < size_ && std::isspace(data_[pos_])) ++pos_;
    std::string token;
    while (pos_ < size_ && !std::isspace(data_[pos_])) {
      if (token.size() >= 256) Fail("a header token is longer than 256 bytes");
      token.push_back(static_cast<char>(data_[pos_++]));
    }
    if (pos_ > kMaxHeaderBytes) Fail("no 'data' line within the first 4096 bytes");
    return token;
  }
  void SkipLine() {
    while (pos_ < size_ && data_[pos_] != '\n') ++pos_;
    if (pos_ < size_) ++pos_;
  }
  uint8_t Byte(const char* context) {
    if (pos_ >= size_) Fail(std::string("the data ends early (") + context + ", byte " +
                             std::to_string(pos_) + " of " + std::to_string(size_) + ")");
    return data_[pos_++];
  }
  float Float(const char* context) {
    uint8_t bytes[4];
    for (uint8_t& b : bytes) b = Byte(context);
    float value;
    std::memcpy(&value, bytes, sizeof(value));
    return value;
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  const std::string& what_;
};

class TreeWalker {
 public:
  TreeWalker(Reader* reader, uint64_t max_nodes, uint64_t max_leaf_columns)
      : in_(*reader), max_nodes_(max_nodes), max_leaf_columns_(max_leaf_columns) {}
  uint64_t nodes() const { return nodes_; }
  uint64_t leaf_columns() const { return leaf_columns_; }

  // A leaf at `depth` is a cube of 2^(16 - depth) voxels a side: it covers 4^(16 - depth)
  // x-y columns, each of which becomes a run when the map is cut into columns. Summed
  // here (at most max_nodes * 4^16, no overflow) and capped once the tree is known whole,
  // so a malformed stream is named as such first.
  void CountLeaf(int depth) {
    const uint64_t columns = uint64_t{1} << (2 * (kTreeDepth - depth));
    leaf_columns_ += columns;
    widest_leaf_ = std::max(widest_leaf_, uint64_t{1} << (kTreeDepth - depth));
  }

  void CheckLeafColumns() const {
    if (leaf_columns_ <= max_leaf_columns_) return;
    throw InputError(in_.what() + ": not a usable map: its leaves cover " +
                     std::to_string(leaf_columns_) + " x-y column cells (a leaf n voxels wide "
                     "counts n^2; the widest is " + std::to_string(widest_leaf_) +
                     " voxels wide), more than the extraction's limit of " +
                     std::to_string(max_leaf_columns_) + " (OctreeStreamLimits::max_leaf_columns, "
                     "about 32 bytes a cell): give a map of the terrain near the robot, or raise "
                     "that limit where the map is loaded");
  }

  void CountNode() {
    if (++nodes_ > max_nodes_) {
      in_.Fail("the tree holds more than " + std::to_string(max_nodes_) + " nodes");
    }
  }

  // .bt: two bytes of 2-bit child codes (01 free leaf, 10 occupied leaf, 11 inner node,
  // 00 no child; low bit first), then the inner children in order.
  void BinaryNode(int depth) {
    const uint8_t lo = in_.Byte("child codes");
    const uint8_t hi = in_.Byte("child codes");
    bool inner[8];
    int children = 0;
    for (int i = 0; i < 8; ++i) {
      const uint8_t byte = i < 4 ? lo : hi;
      const int code = (byte >> (2 * (i % 4))) & 3;
      inner[i] = code == 3;
      if (code != 0) {
        ++children;
        CountNode();
      }
      if (code == 1 || code == 2) CountLeaf(depth + 1);
      if (inner[i] && depth + 1 >= kTreeDepth) {
        in_.Fail("a node at depth " + std::to_string(depth + 1) + " has children (the tree has " +
                 std::to_string(kTreeDepth) + " levels)");
      }
    }
    // OctoMap never writes an inner node without children; its reader would give it a
    // meaningless occupancy.
    if (children == 0 && depth > 0) in_.Fail("an inner node has no children");
    for (int i = 0; i < 8; ++i) {
      if (inner[i]) BinaryNode(depth + 1);
    }
  }

  // .ot: a float log-odds value, one byte with a bit per existing child, then the
  // children in order.
  void FullNode(int depth) {
    const float log_odds = in_.Float("node value");
    if (!std::isfinite(log_odds)) in_.Fail("a node's occupancy is not a finite number");
    const uint8_t mask = in_.Byte("child mask");
    if (mask == 0) CountLeaf(depth);
    if (mask != 0 && depth >= kTreeDepth) {
      in_.Fail("a node at depth " + std::to_string(depth) + " has children (the tree has " +
               std::to_string(kTreeDepth) + " levels)");
    }
    for (int i = 0; i < 8; ++i) {
      if (mask & (1u << i)) {
        CountNode();
        FullNode(depth + 1);
      }
    }
  }

 private:
  Reader& in_;
  uint64_t max_nodes_;
  uint64_t max_leaf_columns_;
  uint64_t nodes_ = 0;
  uint64_t leaf_columns_ = 0;
  uint64_t widest_leaf_ = 0;
};

bool ParseUnsigned(const std::string& token, uint64_t* value) {
  if (token.empty() || token.size() > 19) return false;
  uint64_t v = 0;
  for (char ch : token) {
    if (ch < '0' || ch > '9') return false;
    v = v * 10 + static_cast<uint64_t>(ch - '0');
  }
  *value = v;
  return true;
}

bool ParseDouble(const std::string& token, double* value) {
  if (token.empty()) return false;
  std::istringstream in(token);
  in.imbue(std::locale::classic());
  in >> *value;
  return !in.fail() && in.peek() == std::char_traits<char>::eof();
}

}  // namespace

OctreeStreamInfo CheckOctreeStream(const uint8_t* data, size_t size, const std::string& what,
                                   const OctreeStreamLimits& limits) {
  if (size > limits.max_bytes) {
    throw InputError(what + ": the map is " + std::to_string(size) + " bytes, more than the " +
                     std::to_string(limits.max_bytes) + " byte limit");
  }
  if (size == 0) throw InputError(what + ": the map is empty (0 bytes), not an OctoMap file");
  Reader in(data, size, what);
  OctreeStreamInfo info;
  const std::string first = in.Line();
  if (first.compare(0, std::strlen(kBinaryHeader), kBinaryHeader) == 0) {
    info.kind = OctreeFileKind::kBinary;
  } else if (first.compare(0, std::strlen(kFullHeader), kFullHeader) == 0) {
    info.kind = OctreeFileKind::kFull;
  } else {
    in.Fail(std::string("the first line must be '") + kBinaryHeader + "' (.bt) or '" +
            kFullHeader + "' (.ot)");
  }
  bool have_res = false, have_size = false, have_data = false;
  while (!have_data) {
    const std::string token = in.Token();
    if (token.empty()) in.Fail("the header has no 'data' line");
    if (token == "data") {
      in.SkipLine();
      have_data = true;
    } else if (token[0] == '#') {
      in.SkipLine();
    } else if (token == "id") {
      info.id = in.Token();
    } else if (token == "res") {
      if (!ParseDouble(in.Token(), &info.resolution_m)) in.Fail("'res' is not a number");
      have_res = true;
    } else if (token == "size") {
      if (!ParseUnsigned(in.Token(), &info.declared_nodes)) {
        in.Fail("'size' is not a whole number >= 0");
      }
      have_size = true;
    } else {
      in.SkipLine();  // OctoMap skips unknown header lines too
    }
  }
  // A binary (.bt) file holds only the occupancy bits of each node, whatever tree wrote
  // it: colour and time stamps are not in it, so those trees read as plain OcTrees.
  const bool occupancy_only = info.kind == OctreeFileKind::kBinary &&
                              (info.id == "ColorOcTree" || info.id == "OcTreeStamped");
  if (info.id != "OcTree" && !occupancy_only) {
    in.Fail("tree type (id) is '" + info.id + "'; only OcTree maps are supported (and .bt files of a "
            "ColorOcTree or OcTreeStamped, whose binary data is the same)");
  }
  if (!have_res || !std::isfinite(info.resolution_m) ||
      info.resolution_m < limits.min_resolution_m || info.resolution_m > limits.max_resolution_m) {
    std::ostringstream msg;
    msg << "'res' must be in [" << limits.min_resolution_m << ", " << limits.max_resolution_m
        << "] m" << (have_res ? ", is " + std::to_string(info.resolution_m) : ", is missing");
    in.Fail(msg.str());
  }
  if (!have_size) in.Fail("the header has no 'size'");
  if (info.declared_nodes > limits.max_nodes) {
    in.Fail("'size' declares " + std::to_string(info.declared_nodes) + " nodes, more than the " +
            std::to_string(limits.max_nodes) + " node limit");
  }
  info.data_offset = in.pos();
  TreeWalker walker(&in, limits.max_nodes, limits.max_leaf_columns);
  if (info.declared_nodes > 0) {
    walker.CountNode();  // the root
    if (info.kind == OctreeFileKind::kBinary) {
      walker.BinaryNode(0);
    } else {
      walker.FullNode(0);
    }
  }
  info.nodes = walker.nodes();
  info.leaf_columns = walker.leaf_columns();
  if (info.nodes != info.declared_nodes) {
    in.Fail("the header declares " + std::to_string(info.declared_nodes) +
            " nodes but the data holds " + std::to_string(info.nodes));
  }
  if (!in.AtEnd()) {
    in.Fail(std::to_string(size - in.pos()) + " bytes of unexpected data after the tree");
  }
  walker.CheckLeafColumns();
  return info;
}

}  // namespace mfp
