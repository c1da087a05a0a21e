#include "cli/output_claims.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <map>

#include "mech/errors.h"

namespace mechflow::cli {
namespace {

namespace fs = std::filesystem;

// A path on one line of the record: \, tab and line breaks escaped.
std::string Escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '\\') out += "\\\\";
    else if (c == '\t') out += "\\t";
    else if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else out += c;
  }
  return out;
}

std::string Unescape(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\\' || i + 1 == text.size()) {
      out += text[i];
      continue;
    }
    const char c = text[++i];
    out += c == 't' ? '\t' : c == 'n' ? '\n' : c == 'r' ? '\r' : c;
  }
  return out;
}

// The record, opened for reading and appending and locked until closed.
class LockedRecord {
 public:
  explicit LockedRecord(const OutputFolder& folder) : path_(folder.PathOf(kOutputRecordName)) {
    // O_NOFOLLOW: a symbolic link planted under this name is refused, as for every output
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_APPEND | O_NOFOLLOW | O_CLOEXEC | O_NOCTTY, 0644);
    if (fd_ < 0)
      throw InputError("cannot open '" + path_ + "', the record of which diagram file wrote which files there: " +
                       (errno == ELOOP ? std::string("it is a symbolic link, which is not followed")
                                       : std::strerror(errno)));
    struct stat info {};
    if (::fstat(fd_, &info) != 0 || !S_ISREG(info.st_mode)) {
      ::close(fd_);
      throw InputError("'" + path_ + "' is not a regular file; it is where mechflow records which diagram file "
                       "wrote which files of the folder: remove it");
    }
    while (::flock(fd_, LOCK_EX) != 0) {
      if (errno == EINTR) continue;
      const std::string why = std::strerror(errno);
      ::close(fd_);
      throw InputError("cannot lock '" + path_ + "': " + why);
    }
  }
  ~LockedRecord() { ::close(fd_); }  // the lock goes with the descriptor
  LockedRecord(const LockedRecord&) = delete;
  LockedRecord& operator=(const LockedRecord&) = delete;

  const std::string& path() const { return path_; }

  std::string Read() const {
    std::string text;
    char buffer[65536];
    for (off_t at = 0;;) {
      const ssize_t n = ::pread(fd_, buffer, sizeof buffer, at);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) throw InputError("cannot read '" + path_ + "': " + std::strerror(errno));
      if (n == 0) return text;
      text.append(buffer, static_cast<std::size_t>(n));
      at += n;
    }
  }

  void Append(const std::string& bytes) const {
    for (std::size_t done = 0; done < bytes.size();) {
      const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0)
        throw WriteError("cannot record the output names in '" + path_ +
                         "': " + (n < 0 ? std::strerror(errno) : "nothing more could be written"));
      done += static_cast<std::size_t>(n);
    }
  }

 private:
  std::string path_;
  int fd_ = -1;
};

// stem -> the diagram file that wrote it last.
std::map<std::string, std::string> Parse(const std::string& text, const std::string& path) {
  std::map<std::string, std::string> owners;
  int number = 0;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    start = end + 1;
    ++number;
    if (line.empty() || line[0] == '#') continue;
    const std::size_t tab = line.find('\t');
    if (tab == 0 || tab == std::string::npos || tab + 1 == line.size())
      throw InputError(path + ":" + std::to_string(number) +
                       ": not STEM<tab>DIAGRAM FILE; mechflow writes this record of which diagram file wrote which "
                       "files of the folder: remove the line (or the file, and the folder forgets whose files it "
                       "holds)");
    owners[line.substr(0, tab)] = Unescape(line.substr(tab + 1));
  }
  return owners;
}

}  // namespace

std::string StemOf(const std::string& file_name) { return fs::path(file_name).replace_extension().string(); }

std::string DiagramIdentity(const std::string& diagram_file) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(fs::absolute(diagram_file, ec), ec);
  return ec ? fs::absolute(diagram_file).lexically_normal().string() : canonical.string();
}

void ClaimStems(const OutputFolder& folder, const std::string& diagram_file, const std::vector<OutputStem>& stems,
                bool overwrite, bool record, std::ostream& out) {
  const std::string me = DiagramIdentity(diagram_file);
  const LockedRecord file(folder);
  const std::string text = file.Read();
  const std::map<std::string, std::string> owners = Parse(text, file.path());
  std::string conflicts, added, taken_over;
  std::map<std::string, bool> seen;  // a stem named twice (results and plot both d) is one
  for (const OutputStem& s : stems) {
    if (seen[s.stem]) continue;
    seen[s.stem] = true;
    const auto owner = owners.find(s.stem);
    if (owner != owners.end() && owner->second == me) continue;  // this diagram again: the everyday case
    if (owner != owners.end() && !overwrite) {
      conflicts += (conflicts.empty() ? "" : "; ") + s.stem + ".* written by '" + owner->second +
                   "' (named so here by " + s.origin + ")";
      continue;
    }
    if (owner != owners.end())
      taken_over += (taken_over.empty() ? "" : ", ") + s.stem + ".* (written before by '" + owner->second + "')";
    added += s.stem + "\t" + Escape(me) + "\n";
  }
  if (!conflicts.empty())
    throw InputError(diagram_file + ": not run: the output folder '" + folder.path() + "' holds the files " +
                     conflicts + ", which this diagram file would overwrite. Give another --out, name this "
                     "diagram's outputs otherwise (<diagram name=\"...\">, <output csv=\"...\" plot=\"...\">, "
                     "--results NAME.csv), or pass --overwrite to replace those files");
  if (!record || added.empty()) return;
  if (!text.empty() && text.back() != '\n') added = "\n" + added;  // a line cut short stays its own
  if (text.empty())
    added = "# mechflow: the diagram file that wrote the files STEM.* of this folder (STEM, a tab, the file; the "
            "last line of a stem counts)\n" + added;
  file.Append(added);
  if (!taken_over.empty())
    out << "--overwrite: " << diagram_file << " replaces " << taken_over << " in " << folder.path() << "\n";
}

}  // namespace mechflow::cli
