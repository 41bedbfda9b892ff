#pragma once
// Reads a whole input file (URDF, YAML, map) with a size cap, refusing anything that is
// not a regular file before it is opened for reading: /dev/zero would be read without
// end, a FIFO would block the reader until a writer appears. The file is opened
// non-blocking, so even a path swapped for a FIFO after the check never blocks.
#include <cstddef>
#include <string>

namespace mfp {

// Largest URDF or YAML file read [bytes]: far above any real robot or scenario.
constexpr size_t kMaxTextInputBytes = size_t{16} << 20;

// The bytes of the regular file at `path`. Throws InputError naming `what` (e.g. "URDF",
// "map file") and the path when the path does not exist, is not a regular file (a
// directory, device, FIFO or socket), cannot be read, or holds more than max_bytes.
std::string ReadBoundedRegularFile(const std::string& path, size_t max_bytes,
                                   const std::string& what);

}  // namespace mfp
