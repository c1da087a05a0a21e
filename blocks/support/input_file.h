#pragma once
// Reading the files a diagram names: the diagram itself, mechanism files,
// Lua files, table files.
//
// A diagram may come from someone else, so a file it names must be a regular
// file of at most kMaxInputFileBytes: a FIFO nobody writes to, a device such
// as /dev/zero or a folder would block or never end. The file is opened
// without blocking and checked on the open descriptor (no race between the
// check and the read).
//
// Nor may it name whatever the user can read (~/.ssh/id_rsa, /etc/shadow as
// root): a file a diagram names must lie in the diagram's folder tree, or in
// a tree the user allows on the command line (--allow-read DIR). Files the
// user names on the command line (the diagram, a results file) are not
// confined.

#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace mechflow::blocks {

inline constexpr std::size_t kMaxInputFileBytes = std::size_t(64) << 20;

// The bytes of `path`, a file the user chose. Throws InputError "WHAT 'path':
// why" when it cannot be opened, is not a regular file, or is larger than the
// limit.
std::string ReadInputFile(const std::string& path, const std::string& what);

// A file read through a policy: what export-fmu packs (fmi/export.h).
struct FileRead {
  std::string path;            // as named: the naming file's folder joined with the name, normalised
  std::filesystem::path real;  // symbolic links resolved
  std::string where;           // the naming line ("d.xml:12: block 'b' parameter 'file'")
};

// The folder trees a diagram may read files from: its own folder's and those
// given by --allow-read. Each is taken by its real path (symbolic links
// resolved) when the policy is made. It keeps the files read through it.
class ReadPolicy {
 public:
  // Throws InputError when a folder does not exist.
  ReadPolicy(const std::string& diagram_file, const std::vector<std::string>& allowed_folders);

  // Whether the real path `path` lies in one of the trees.
  bool Allows(const std::filesystem::path& path) const;
  std::string DiagramFolder() const { return roots_.front().string(); }

  // Every file read through the policy (ReadNamedFile), in order, repeats included.
  const std::vector<FileRead>& files_read() const { return files_read_; }
  void Record(FileRead file) const { files_read_.push_back(std::move(file)); }

 private:
  std::vector<std::filesystem::path> roots_;  // real paths; the diagram's folder first
  mutable std::vector<FileRead> files_read_;  // a record, not the policy: reading adds to it
};

struct NamedFile {
  std::string path;  // the name resolved against the naming file's folder
  std::string text;
};

// The file a diagram names `name` at `where` ("d.xml:12: block 'b' parameter
// 'file'"), relative to `folder` (the naming file's). InputError naming
// `where` when it does not exist, is no regular file or too large, or lies
// outside the policy's trees once symbolic links are resolved. The check is
// made on the opened file, so a link swapped in between cannot lead out.
NamedFile ReadNamedFile(const std::string& name, const std::string& folder, const ReadPolicy& policy,
                        const std::string& where);

}  // namespace mechflow::blocks
