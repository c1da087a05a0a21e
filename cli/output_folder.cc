#include "cli/output_folder.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace mechflow::cli {
namespace {

std::string Why() { return std::strerror(errno); }

bool IsRegular(int fd) {
  struct stat info {};
  return ::fstat(fd, &info) == 0 && S_ISREG(info.st_mode);
}

}  // namespace

std::string OutputFolder::NameProblem(const std::string& name) {
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos)
    return "is not a plain file name";
  if (name.find_first_of("-+<|") == 0)
    return "begins with '" + name.substr(0, 1) +
           "', which gnuplot would take for an option, a pseudo-file or a command; a file name may not begin "
           "with '-', '+', '<' or '|' (rename it)";
  return "";
}

namespace {

void CheckName(const OutputFolder& folder, const std::string& name) {
  if (const std::string problem = OutputFolder::NameProblem(name); !problem.empty())
    throw InputError("cannot write '" + folder.PathOf(name) + "': the name " + problem);
}

}  // namespace

OutputFolder::OutputFolder(const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw InputError("cannot create the output folder '" + folder + "': " + ec.message());
  if (!fs::is_directory(folder, ec)) throw InputError("the output folder '" + folder + "' is not a folder");
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw InputError("cannot write into the output folder '" + folder + "': " + Why());
  path_ = fs::absolute(folder).lexically_normal().string();
  if (path_.size() > 1 && path_.back() == '/') path_.pop_back();
}

int OutputFolder::Create(const std::string& name) const {
  CheckName(*this, name);
  const std::string path = PathOf(name);
  // O_NOFOLLOW: a symbolic link planted under this name is refused, not followed
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC | O_NOCTTY, 0644);
  if (fd < 0) {
    if (errno == ELOOP) throw WriteError("cannot write '" + path + "': it is a symbolic link, which is not followed");
    throw WriteError("cannot write '" + path + "': " + Why());
  }
  return fd;
}

void OutputFolder::Write(const std::string& name, const std::string& bytes) const {
  const std::string path = PathOf(name);
  const int fd = Create(name);
  // a cut file is removed (not a device the name may stand for: /dev/full)
  const bool regular = IsRegular(fd);
  const std::string removed = regular ? "; the incomplete file is removed" : "";
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = n < 0 ? Why() : "nothing more could be written";
      ::close(fd);
      if (regular) ::unlink(path.c_str());
      throw WriteError("error writing '" + path + "' after " + std::to_string(done) + " of " +
                       std::to_string(bytes.size()) + " bytes: " + why + removed);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) {
    const std::string why = Why();
    if (regular) ::unlink(path.c_str());
    throw WriteError("error writing '" + path + "' (at close): " + why + removed);
  }
}

void OutputFolder::Clear(const std::string& name) const {
  CheckName(*this, name);
  const std::string path = PathOf(name);
  struct stat info {};
  if (::lstat(path.c_str(), &info) != 0) return;  // not there
  if (S_ISLNK(info.st_mode))
    throw WriteError("cannot write '" + path + "': it is a symbolic link, which is not followed");
  if (!S_ISREG(info.st_mode)) throw WriteError("cannot write '" + path + "': it is not a regular file");
  if (::unlink(path.c_str()) != 0) throw WriteError("cannot replace '" + path + "': " + Why());
}

bool OutputFolder::HasFile(const std::string& name) const {
  struct stat info {};
  return ::lstat(PathOf(name).c_str(), &info) == 0 && S_ISREG(info.st_mode) && info.st_size > 0;
}

void OutputFolder::RemoveCut(const std::string& name) const {
  struct stat info {};
  if (::lstat(PathOf(name).c_str(), &info) == 0 && S_ISREG(info.st_mode)) ::unlink(PathOf(name).c_str());
}

}  // namespace mechflow::cli
