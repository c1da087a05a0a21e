#pragma once
// Instance paths: the names of what a subsystem or part instance holds,
// "d[1].c", "chain.s[2].mu" -- segments that are Lua names, each perhaps
// with a 0-based index, joined by '.'.
//
// Expressions are Lua, where such a path is no name; an identifier with a
// path is known to Lua by its path's Lua name, the segments joined by "__"
// ("d__1__c"). Names a diagram writes may not contain "__", so no written
// name can meet one of these.

#include <cctype>
#include <string>

namespace mechflow::scripting {

// True when `name` has the shape of a path (a '.' or '[' in it).
inline bool IsInstancePath(const std::string& name) { return name.find_first_of(".[") != std::string::npos; }

// "" when `path` is a well-formed path, else what is wrong with it.
inline std::string InstancePathProblem(const std::string& path) {
  std::size_t i = 0;
  while (true) {
    const std::size_t start = i;
    if (i >= path.size() || !(std::isalpha(static_cast<unsigned char>(path[i])) || path[i] == '_'))
      return "each part of a path starts with a letter or '_'";
    while (i < path.size() && (std::isalnum(static_cast<unsigned char>(path[i])) || path[i] == '_')) ++i;
    if (path.substr(start, i - start).find("__") != std::string::npos) return "names may not contain \"__\"";
    if (i < path.size() && path[i] == '[') {
      const std::size_t digits = ++i;
      while (i < path.size() && std::isdigit(static_cast<unsigned char>(path[i]))) ++i;
      if (i == digits || i >= path.size() || path[i] != ']') return "an index is written [0], [1], ...";
      ++i;
    }
    if (i == path.size()) return "";
    if (path[i] != '.') return "parts of a path are joined by '.'";
    ++i;
  }
}

// The Lua name of a well-formed path: "d[1].c" -> "d__1__c".
inline std::string InstancePathLuaName(const std::string& path) {
  std::string out;
  for (const char c : path) {
    if (c == '.' || c == '[') out += "__";
    else if (c != ']') out += c;
  }
  return out;
}

}  // namespace mechflow::scripting
