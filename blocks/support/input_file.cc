#include "blocks/support/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "blocks/support/excerpt.h"
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

// Opens `path` for reading without blocking (a FIFO without a writer) and
// without making it the controlling terminal.
int OpenForReading(const std::string& path) {
  return ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
}

// The bytes of the open regular file `fd`, named `name` in messages.
std::string ReadOpened(int fd, const std::string& name) {
  struct stat info {};
  if (::fstat(fd, &info) != 0) throw InputError("cannot read " + name + ": " + std::strerror(errno));
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
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
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

// The real path of the file open as `fd`: what the kernel opened, whatever
// links the name went through and however they changed since. Without
// /proc, the real path of `path` if it is the same file (a link swapped
// between the two looks is then caught by the comparison).
std::filesystem::path OpenedPath(int fd, const std::filesystem::path& path) {
  char link[64];
  std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  std::error_code error;
  std::filesystem::path real = std::filesystem::read_symlink(link, error);
  if (!error && real.is_absolute()) return real;
  real = std::filesystem::canonical(path, error);
  struct stat opened {}, named {};
  if (error || ::fstat(fd, &opened) != 0 || ::stat(real.c_str(), &named) != 0 || opened.st_dev != named.st_dev ||
      opened.st_ino != named.st_ino)
    return {};
  return real;
}

}  // namespace

std::string ReadInputFile(const std::string& path, const std::string& what) {
  const std::string name = what + " '" + path + "'";
  const Descriptor fd(OpenForReading(path));
  if (fd.get() < 0) throw InputError("cannot open " + name + ": " + std::strerror(errno));
  return ReadOpened(fd.get(), name);
}

ReadPolicy::ReadPolicy(const std::string& diagram_file, const std::vector<std::string>& allowed_folders) {
  std::filesystem::path folder = std::filesystem::path(diagram_file).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code error;
  const std::filesystem::path real = std::filesystem::weakly_canonical(folder, error);
  roots_.push_back(error ? std::filesystem::absolute(folder).lexically_normal() : real);
  for (const std::string& allowed : allowed_folders) {
    const std::filesystem::path root = std::filesystem::canonical(allowed, error);
    if (error || !std::filesystem::is_directory(root))
      throw InputError("--allow-read '" + Excerpt(allowed, kPathExcerptLength) + "': no such folder");
    roots_.push_back(root);
  }
}

bool ReadPolicy::Allows(const std::filesystem::path& path) const {
  return std::any_of(roots_.begin(), roots_.end(), [&](const std::filesystem::path& root) {
    // component by component: /data/d is not inside /data/diagram
    auto p = path.begin();
    for (auto r = root.begin(); r != root.end(); ++r, ++p) {
      if (r->empty()) continue;  // the empty last component of "/data/d/"
      if (p == path.end() || *p != *r) return false;
    }
    return true;
  });
}

NamedFile ReadNamedFile(const std::string& name, const std::string& folder, const ReadPolicy& policy,
                        const std::string& where) {
  const std::string quoted = "'" + Excerpt(name) + "'";
  if (name.empty()) throw InputError(where + ": the file name is empty");
  const std::filesystem::path path = (std::filesystem::path(folder) / name).lexically_normal();
  const auto outside = [&](const std::filesystem::path& real) {
    return InputError(where + ": file " + quoted + " lies outside the diagram's folder " +
                      Excerpt(policy.DiagramFolder(), kPathExcerptLength) +
                      (real.empty() ? std::string() : " (it is " + Excerpt(real.string(), kPathExcerptLength) + ")") +
                      "; a diagram reads files in its own folder tree only: copy the file there, or allow its "
                      "folder with --allow-read DIR");
  };
  // by name first, so that nothing outside is even opened (opening some devices does something)
  std::error_code error;
  const std::filesystem::path named = std::filesystem::canonical(path, error);
  if (error == std::errc::no_such_file_or_directory || error == std::errc::not_a_directory)
    throw InputError(where + ": file " + quoted + " not found (looked for " + Excerpt(path.string(), kPathExcerptLength) + ")");
  if (error) throw InputError(where + ": cannot open file " + quoted + ": " + error.message());
  if (!policy.Allows(named)) throw outside(named);
  // then the file opened: a link swapped in since cannot lead out
  const Descriptor fd(OpenForReading(path.string()));
  if (fd.get() < 0) throw InputError(where + ": cannot open file " + quoted + ": " + std::strerror(errno));
  const std::filesystem::path real = OpenedPath(fd.get(), path);
  if (!policy.Allows(real)) throw outside(real);
  NamedFile file{path.string(), ReadOpened(fd.get(), where + ": file " + quoted)};
  policy.Record({file.path, real, where});
  return file;
}

}  // namespace mechflow::blocks
