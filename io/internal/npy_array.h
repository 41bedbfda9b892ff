#pragma once
// A small, bounded reader of 2-D numpy arrays (.npy, format versions 1 to 3): float32 or
// float64, little-endian, C or Fortran order. Sizes are checked against the caller's limit
// and against the file's length before anything is allocated. No numpy needed.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mfp {

struct NpyArray {
  size_t rows = 0;            // shape[0]
  size_t cols = 0;            // shape[1]
  std::vector<float> values;  // values[r * cols + c] (C order, whatever the file's order)
};

// Throws InputError naming `what` (the file) when the bytes are not a .npy file, the
// header is malformed or longer than 64 KiB, the array is not 2-D, its dtype is not
// '<f4' or '<f8', it has more than max_cells elements, or the data is shorter or longer
// than the shape says.
NpyArray ParseNpy(const std::vector<uint8_t>& bytes, const std::string& what, size_t max_cells);

// Reads and parses a file; throws InputError when it is missing, unreadable or larger
// than the biggest array max_cells allows (8 bytes a cell plus the header).
NpyArray ReadNpyFile(const std::string& path, size_t max_cells);

// The bytes of a .npy file (version 1.0, '<f4', C order): tests and examples write maps.
std::vector<uint8_t> NpyBytes(const NpyArray& array);

}  // namespace mfp
