#pragma once
// OutputFolder: where a run writes its files, and the only way it writes them.
//
// The folder comes from the command line (--out) and may be anywhere; the
// names inside it come from the diagram, which may come from someone else, so
// they are plain file names (checked by the loader) and every file is opened
// without following a symbolic link: a shared diagram cannot write outside
// the folder. Every write is checked to the last byte and the close, so a
// full disk is an error naming the file, never a silently short file: a
// file written whole (Write) is removed when cut; the results CSV, written
// row by row (cli/results_file.h), is kept and named as cut.
//
// No name may begin with '-', '+', '<' or '|': gnuplot, which reads and
// draws these files, would take it for an option, a pseudo-file or a command.

#include <string>

#include "mech/errors.h"

namespace mechflow::cli {

// A file that could not be written completely (exit code 1: the run's
// results exist, but not all of them reached the disk).
class WriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class OutputFolder {
 public:
  // Creates the folder if needed and checks that files can be made in it;
  // throws InputError (exit 2) when it cannot, before anything has run.
  explicit OutputFolder(const std::string& folder);

  // "" when `name` may be a file in the folder, else why not (a plain file
  // name, not beginning with '-', '+', '<' or '|').
  static std::string NameProblem(const std::string& name);

  const std::string& path() const { return path_; }  // absolute
  std::string PathOf(const std::string& name) const { return path_ + "/" + name; }

  // Replaces the file `name` by `bytes`. Throws WriteError saying why
  // (a symbolic link in the way, no space left, ...); a file cut short is
  // removed. Every method throws InputError for a name NameProblem refuses.
  void Write(const std::string& name, const std::string& bytes) const;

  // Creates (or truncates) `name` for writing and returns its descriptor,
  // refusing a symbolic link as Write does. Throws WriteError.
  int Create(const std::string& name) const;

  // Removes `name` if it is there, so a program run to make it (gnuplot)
  // can be seen to have made it; refuses (WriteError) when `name` is a
  // symbolic link or not a regular file, which that program would follow.
  void Clear(const std::string& name) const;

  // True when `name` is a regular, non-empty file in the folder.
  bool HasFile(const std::string& name) const;

  // Removes the regular file `name` (one found cut short); quietly does
  // nothing for anything else.
  void RemoveCut(const std::string& name) const;

 private:
  std::string path_;
};

}  // namespace mechflow::cli
