#include "blocks/support/excerpt.h"

#include <cstdio>

namespace mechflow::blocks {
namespace {

// Length of the well-formed UTF-8 sequence at `s[i]` (2 to 4 bytes), or 0.
std::size_t Utf8Length(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(i);
  std::size_t length = 0;
  unsigned c = 0, least = 0;
  if ((b & 0xE0) == 0xC0) length = 2, c = b & 0x1F, least = 0x80;
  else if ((b & 0xF0) == 0xE0) length = 3, c = b & 0x0F, least = 0x800;
  else if ((b & 0xF8) == 0xF0) length = 4, c = b & 0x07, least = 0x10000;
  else return 0;
  if (i + length > s.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    c = (c << 6) | (byte(i + k) & 0x3F);
  }
  if (c < least || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) return 0;
  return length;
}

std::string Escaped(std::string_view text, std::size_t max_length, bool keep_lines) {
  std::string out;
  std::size_t characters = 0, i = 0;
  for (; i < text.size() && characters < max_length; ++characters) {
    const unsigned char b = static_cast<unsigned char>(text[i]);
    if (b >= 0x20 && b < 0x7f) {
      out += text[i++];
    } else if (keep_lines && (b == '\n' || b == '\t')) {
      out += text[i++];
    } else if (const std::size_t n = b >= 0x80 ? Utf8Length(text, i) : 0; n > 0) {
      out.append(text.substr(i, n));
      i += n;
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", b);
      out += hex;
      ++i;
    }
  }
  if (i < text.size()) out += "...";
  return out;
}

}  // namespace

std::string Excerpt(std::string_view text, std::size_t max_length) { return Escaped(text, max_length, false); }

std::string MessageExcerpt(std::string_view text, std::size_t max_length) { return Escaped(text, max_length, true); }

std::string_view WithoutByteOrderMark(std::string_view text) {
  return text.substr(0, 3) == "\xEF\xBB\xBF" ? text.substr(3) : text;
}

}  // namespace mechflow::blocks
