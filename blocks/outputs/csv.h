#pragma once
// CSV as RFC 4180 reads it, so spreadsheets and pandas read ours: a field holding a comma, a
// quote or a line break is quoted (quotes doubled); a number is written in
// the shortest form that reads back to the same double (std::to_chars), and
// a negative zero as 0.

#include <charconv>
#include <string>

namespace mechflow::blocks {

inline std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

inline std::string CsvNumber(double v) {
  if (v == 0.0) return "0";  // also -0
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

}  // namespace mechflow::blocks
