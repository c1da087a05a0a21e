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

// True when `name` holds [*], which stands for every index.
inline bool IsInstancePattern(const std::string& name) { return name.find("[*]") != std::string::npos; }

// True when `spelling` is `pattern` with each [*] an index [k] (letters in
// any case, as identifiers are found).
inline bool MatchesInstancePattern(const std::string& pattern, const std::string& spelling) {
  std::size_t p = 0, s = 0;
  while (p < pattern.size()) {
    if (pattern.compare(p, 3, "[*]") == 0) {
      if (s >= spelling.size() || spelling[s] != '[') return false;
      const std::size_t digits = ++s;
      while (s < spelling.size() && std::isdigit(static_cast<unsigned char>(spelling[s]))) ++s;
      if (s == digits || s >= spelling.size() || spelling[s] != ']') return false;
      ++s;
      p += 3;
      continue;
    }
    if (s >= spelling.size() || std::tolower(static_cast<unsigned char>(pattern[p])) !=
                                    std::tolower(static_cast<unsigned char>(spelling[s])))
      return false;
    ++p, ++s;
  }
  return s == spelling.size();
}

// `text` (an expression) with the Lua names of paths written as the paths
// ("1.25*d__1__mu" -> "1.25*d[1].mu"), for what a user reads.
inline std::string WithInstancePaths(const std::string& text) {
  if (text.find("__") == std::string::npos) return text;
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    const bool starts_name = (std::isalpha(static_cast<unsigned char>(text[i])) || text[i] == '_') &&
                             (i == 0 || !(std::isalnum(static_cast<unsigned char>(text[i - 1])) || text[i - 1] == '_'));
    if (!starts_name) {
      out += text[i++];
      continue;
    }
    std::size_t end = i;
    while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_')) ++end;
    const std::string name = text.substr(i, end - i);
    i = end;
    if (name.find("__") == std::string::npos || name.front() == '_') {
      out += name;
      continue;
    }
    for (std::size_t start = 0;;) {
      const std::size_t cut = name.find("__", start);
      const std::string segment = name.substr(start, cut == std::string::npos ? std::string::npos : cut - start);
      const bool index = !segment.empty() && std::isdigit(static_cast<unsigned char>(segment[0]));
      out += index ? "[" + segment + "]" : (start == 0 ? "" : ".") + segment;
      if (cut == std::string::npos) break;
      start = cut + 2;
    }
  }
  return out;
}

}  // namespace mechflow::scripting
