#include "blocks/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "mech/errors.h"

namespace mechflow::blocks {
namespace {

// Closes the descriptor on every way out.
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

}  // namespace

std::string ReadInputFile(const std::string& path, const std::string& what) {
  const std::string name = what + " '" + path + "'";
  // O_NONBLOCK: opening a FIFO without a writer must not wait
  const Descriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
  if (fd.get() < 0) throw InputError("cannot open " + name + ": " + std::strerror(errno));
  struct stat info {};
  if (::fstat(fd.get(), &info) != 0) throw InputError("cannot read " + name + ": " + std::strerror(errno));
  if (!S_ISREG(info.st_mode))
    throw InputError(name + " is not a regular file (" +
                     (S_ISDIR(info.st_mode)    ? "a folder"
                      : S_ISFIFO(info.st_mode) ? "a pipe"
                      : S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode) ? "a device"
                                                                         : "a special file") +
                     "); give the path of a file");
  if (static_cast<std::size_t>(info.st_size) > kMaxInputFileBytes)
    throw InputError(name + " has " + std::to_string(info.st_size) + " bytes; input files may have at most " +
                     std::to_string(kMaxInputFileBytes >> 20) + " MiB");
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InputError("cannot read " + name + ": " + std::strerror(errno));
    }
    text.append(buffer, static_cast<std::size_t>(n));
    // the file may grow while it is read
    if (text.size() > kMaxInputFileBytes)
      throw InputError(name + " grew past " + std::to_string(kMaxInputFileBytes >> 20) + " MiB while it was read");
  }
  return text;
}

}  // namespace mechflow::blocks
