#pragma once
// The tokens of Lua source text, as far as mechflow's scanners of
// expressions and Lua-block code need them (compiled_expression.cc,
// lua_block.cc): each finds the names a piece of code uses and rewrites
// identifier names, so both must agree on where strings, comments and
// numbers begin and end. This is no parser: it never rejects text; Lua's own
// compiler reports syntax errors.

#include <cctype>
#include <cstddef>
#include <string>

namespace mechflow::scripting {

enum class LuaToken { kSpace, kComment, kString, kNumber, kName, kPunctuation };

inline bool IsNameStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
inline bool IsNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Length of the long bracket opening at `i` ("[[" -> 2, "[==[" -> 4), or 0.
inline std::size_t LongBracketOpen(const std::string& s, std::size_t i) {
  if (i >= s.size() || s[i] != '[') return 0;
  std::size_t j = i + 1;
  while (j < s.size() && s[j] == '=') ++j;
  return j < s.size() && s[j] == '[' ? j + 1 - i : 0;
}

// End (one past) of the long string or comment whose opening bracket of
// `open_length` characters starts at `i`; the text's end if unclosed.
inline std::size_t LongBracketEnd(const std::string& s, std::size_t i, std::size_t open_length) {
  const std::string close = "]" + std::string(open_length - 2, '=') + "]";
  const std::size_t end = s.find(close, i + open_length);
  return end == std::string::npos ? s.size() : end + close.size();
}

// The token starting at `i` (< s.size()) and its end (one past) in *end.
// Names include keywords (tell them apart with IsLuaName). A sign belongs to
// a number after its exponent (e, or p for hexadecimal). "..", "..." and
// "::" are one punctuation token, every other punctuation character one each.
inline LuaToken NextLuaToken(const std::string& s, std::size_t i, std::size_t* end) {
  const char c = s[i];
  std::size_t j = i + 1;
  const auto digit = [&](std::size_t k) { return k < s.size() && std::isdigit(static_cast<unsigned char>(s[k])); };
  LuaToken kind = LuaToken::kPunctuation;
  if (std::isspace(static_cast<unsigned char>(c))) {
    kind = LuaToken::kSpace;
  } else if (c == '-' && j < s.size() && s[j] == '-') {
    const std::size_t open = LongBracketOpen(s, i + 2);
    j = open ? LongBracketEnd(s, i + 2, open) : std::min(s.find('\n', i), s.size());
    kind = LuaToken::kComment;
  } else if (c == '"' || c == '\'') {  // ends at its quote, or unclosed at the line's end
    while (j < s.size() && s[j] != c && s[j] != '\n') j += s[j] == '\\' ? 2 : 1;
    j = std::min(j + 1, s.size());
    kind = LuaToken::kString;
  } else if (const std::size_t open = LongBracketOpen(s, i)) {
    j = LongBracketEnd(s, i, open);
    kind = LuaToken::kString;
  } else if (digit(i) || (c == '.' && digit(i + 1))) {
    const bool hex = c == '0' && j < s.size() && (s[j] == 'x' || s[j] == 'X');
    const char exponent = hex ? 'p' : 'e';
    while (j < s.size() && (IsNameChar(s[j]) || s[j] == '.' ||
                            ((s[j] == '+' || s[j] == '-') && std::tolower(static_cast<unsigned char>(s[j - 1])) == exponent)))
      ++j;
    kind = LuaToken::kNumber;
  } else if (IsNameStart(c)) {
    while (j < s.size() && IsNameChar(s[j])) ++j;
    kind = LuaToken::kName;
  } else {
    while (j < s.size() && j - i < 3 && (c == '.' || c == ':') && s[j] == c) ++j;
  }
  *end = j;
  return kind;
}

}  // namespace mechflow::scripting
