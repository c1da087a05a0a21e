#pragma once
// `--vary s[*].mu=...`: a name in which [*] stands for every index, so that
// one option varies the same parameter of every instance of an array
// (s[0].mu, s[1].mu, ...) alike.

#include <cctype>
#include <string>
#include <vector>

#include "scripting/identifiers.h"
#include "scripting/instance_path.h"

namespace mechflow::cli {

inline bool IsVaryPattern(const std::string& name) { return scripting::IsInstancePattern(name); }

// True when `spelling` is `pattern` with each [*] an index [k].
inline bool MatchesVaryPattern(const std::string& pattern, const std::string& spelling) {
  return scripting::MatchesInstancePattern(pattern, spelling);
}

// `spelling` with every index written [*]: "s[2].mu" -> "s[*].mu", what a
// pattern that misses is compared with for a suggestion.
inline std::string AsVaryPattern(const std::string& spelling) {
  std::string out;
  for (std::size_t i = 0; i < spelling.size(); ++i) {
    std::size_t j = i + 1;
    while (spelling[i] == '[' && j < spelling.size() && std::isdigit(static_cast<unsigned char>(spelling[j]))) ++j;
    if (spelling[i] == '[' && j > i + 1 && j < spelling.size() && spelling[j] == ']') {
      out += "[*]";
      i = j;
    } else {
      out += spelling[i];
    }
  }
  return out;
}

// The identifiers `pattern` matches, in the table's order.
inline std::vector<int> MatchVaryPattern(const scripting::IdentifierTable& ids, const std::string& pattern) {
  std::vector<int> found;
  for (int i = 0; i < ids.size(); ++i)
    if (MatchesVaryPattern(pattern, ids.spelling(i))) found.push_back(i);
  return found;
}

}  // namespace mechflow::cli
