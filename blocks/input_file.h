#pragma once
// Reading the files a diagram names: the diagram itself, mechanism files,
// Lua files, table files.
//
// A diagram may come from someone else, so a file it names must be a regular
// file of at most kMaxInputFileBytes: a FIFO nobody writes to, a device such
// as /dev/zero or a folder would block or never end. The file is opened
// without blocking and checked on the open descriptor (no race between the
// check and the read).

#include <cstddef>
#include <string>

namespace mechflow::blocks {

inline constexpr std::size_t kMaxInputFileBytes = std::size_t(64) << 20;

// The bytes of `path`. Throws InputError "WHAT 'path': why" when it cannot be
// opened, is not a regular file, or is larger than the limit.
std::string ReadInputFile(const std::string& path, const std::string& what);

}  // namespace mechflow::blocks
