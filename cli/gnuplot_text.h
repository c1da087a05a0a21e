#pragma once
// Text for gnuplot scripts.

#include <string>

namespace mechflow::cli {

// A gnuplot single-quoted string, which gnuplot reads without backquote
// substitution or escapes: the quote itself is doubled, and a control
// character (a line break would end the string's line, and the next line
// would be a gnuplot command) becomes '?'. Diagram texts hold none (the
// loader refuses them); this keeps the script safe whatever it is given.
inline std::string GnuplotQuote(const std::string& s) {
  std::string out = "'";
  for (const char c : s) {
    if (c == '\'') out += "''";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) out += '?';
    else out += c;
  }
  return out + "'";
}

}  // namespace mechflow::cli
