#include "base/bounded_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "base/check.h"

namespace mfp {
namespace {

std::string KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void Refuse(const std::string& path, const std::string& what,
                         const std::string& problem) {
  throw InputError(path + ": " + problem + " (the " + what + ")");
}

// Closes the descriptor on every path out.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

void RequireRegular(const struct stat& st, const std::string& path, const std::string& what,
                    size_t max_bytes) {
  if (!S_ISREG(st.st_mode)) {
    Refuse(path, what, "is " + KindOf(st.st_mode) + ", not a regular file; give the path of a file");
  }
  if (st.st_size < 0 || static_cast<unsigned long long>(st.st_size) > max_bytes) {
    Refuse(path, what, "is " + std::to_string(st.st_size) + " bytes, more than the limit of " +
                           std::to_string(max_bytes) + " bytes");
  }
}

}  // namespace

std::string ReadBoundedRegularFile(const std::string& path, size_t max_bytes,
                                   const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    Refuse(path, what, errno == ENOENT ? std::string("no such file")
                                       : std::string("cannot be read: ") + std::strerror(errno));
  }
  RequireRegular(st, path, what, max_bytes);
  // Non-blocking: a FIFO put in the file's place after stat() is not waited on.
  const Descriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (fd.get() < 0) Refuse(path, what, std::string("cannot be opened: ") + std::strerror(errno));
  if (::fstat(fd.get(), &st) != 0) Refuse(path, what, "cannot be read");
  RequireRegular(st, path, what, max_bytes);
  std::string bytes;
  bytes.reserve(static_cast<size_t>(st.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(fd.get(), buffer, sizeof(buffer));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) Refuse(path, what, std::string("could not be read: ") + std::strerror(errno));
    if (got == 0) break;
    // The file may have grown since fstat(): the cap holds for what is read.
    if (bytes.size() + static_cast<size_t>(got) > max_bytes) {
      Refuse(path, what, "holds more than the limit of " + std::to_string(max_bytes) + " bytes");
    }
    bytes.append(buffer, static_cast<size_t>(got));
  }
  return bytes;
}

}  // namespace mfp
