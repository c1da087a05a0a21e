#pragma once
// The subsystem and part instances of a flattened diagram as a tree, for
// `mechflow check` (an indented list) and `mechflow graph` (nested clusters).
// An instance's parent is the longest proper prefix of its path, up to a
// '.', that is an instance too: "chain.s[2]" lies in "chain"; a part's path
// starts with its mechanism block's name ("m.arm[0]"), which is none.

#include <map>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "diagrams/description.h"

namespace mechflow::cli {

class InstanceTree {
 public:
  explicit InstanceTree(std::vector<std::string> paths);

  const std::vector<std::string>& paths() const { return paths_; }
  const std::vector<int>& roots() const { return roots_; }
  const std::vector<int>& children(int i) const { return children_.at(i); }
  // The innermost instance `name` lies in ("d[1].fr" lies in "d[1]"), or -1;
  // as many lookups as the name has dots.
  int Enclosing(std::string_view name) const;

 private:
  std::vector<std::string> paths_;
  std::map<std::string, int, std::less<>> index_;
  std::vector<int> roots_;
  std::vector<std::vector<int>> children_;
};

// "instances:" and a line per instance, indented by its depth: its path,
// kind, file and the line that includes it. Nothing when there are none.
void PrintInstanceTree(const std::vector<diagrams::InstanceDesc>& instances, std::ostream& out);

}  // namespace mechflow::cli
