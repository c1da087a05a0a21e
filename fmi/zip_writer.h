#pragma once
// The .fmu archive: a zip file (libzip, Debian's libzip-dev) made of named
// entries, each from memory or from a file, deflated.

#include <string>
#include <utility>
#include <vector>

namespace mechflow::fmi {

struct ZipEntry {
  std::string name;     // the path inside the archive, '/'-separated
  std::string content;  // the bytes, when `file` is empty
  std::string file;     // else read from this file
};

// Writes `entries` to `path` (replaced if it exists). Throws std::runtime_error
// naming the path and libzip's reason when it cannot.
void WriteZip(const std::string& path, const std::vector<ZipEntry>& entries);

}  // namespace mechflow::fmi
