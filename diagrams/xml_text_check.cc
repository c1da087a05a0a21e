#include "diagrams/xml_text_check.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "blocks/support/excerpt.h"
#include "mech/errors.h"

namespace mechflow::diagrams {
namespace {

bool AllowedCharacter(std::uint32_t c) {
  return c == 0x9 || c == 0xA || c == 0xD || (c >= 0x20 && c <= 0xD7FF) || (c >= 0xE000 && c <= 0xFFFD) ||
         (c >= 0x10000 && c <= 0x10FFFF);
}

// Length of the UTF-8 sequence starting at `s[i]` and its code point, or 0
// when the bytes are not UTF-8.
int DecodeUtf8(const std::string& s, std::size_t i, std::uint32_t* code) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(i);
  int length = 0;
  std::uint32_t c = 0, least = 0;
  if (b < 0x80) {
    *code = b;
    return 1;
  } else if ((b & 0xE0) == 0xC0) {
    length = 2, c = b & 0x1F, least = 0x80;
  } else if ((b & 0xF0) == 0xE0) {
    length = 3, c = b & 0x0F, least = 0x800;
  } else if ((b & 0xF8) == 0xF0) {
    length = 4, c = b & 0x07, least = 0x10000;
  } else {
    return 0;
  }
  if (i + length > s.size()) return 0;
  for (int k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    c = (c << 6) | (byte(i + k) & 0x3F);
  }
  if (c < least || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) return 0;
  *code = c;
  return length;
}

class TextChecker {
 public:
  TextChecker(const std::string& text, const std::string& file) : text_(text), file_(file) {}

  void Run() {
    CheckEncoding();
    for (std::size_t i = 0; i < text_.size();) {
      if (text_[i] != '<' && text_[i] != '&') {
        ++i;
      } else if (StartsWith(i, "<!--")) {
        i = Skip(i, "-->", "a comment");
      } else if (StartsWith(i, "<![CDATA[")) {
        i = Skip(i, "]]>", "a CDATA section");
      } else if (StartsWith(i, "<?")) {
        i = Skip(i, "?>", "a processing instruction");
      } else if (StartsWith(i, "<!DOCTYPE")) {
        Fail(i, "a DOCTYPE declaration; diagrams take none (entities and external references are not supported)");
      } else if (text_[i] == '&') {
        i = CheckReference(i);
      } else {
        ++i;
      }
    }
  }

 private:
  [[noreturn]] void Fail(std::size_t at, const std::string& what) const {
    int line = 1;
    for (std::size_t k = 0; k < at && k < text_.size(); ++k) line += text_[k] == '\n';
    throw InputError(file_ + ":" + std::to_string(line) + ": " + what);
  }

  bool StartsWith(std::size_t i, const char* prefix) const { return text_.compare(i, std::strlen(prefix), prefix) == 0; }

  std::size_t Skip(std::size_t i, const char* end, const char* what) const {
    const std::size_t at = text_.find(end, i);
    if (at == std::string::npos) Fail(i, std::string(what) + " that is never closed (no '" + end + "')");
    return at + std::strlen(end);
  }

  void CheckEncoding() const {
    for (std::size_t i = 0; i < text_.size();) {
      std::uint32_t c = 0;
      const int n = DecodeUtf8(text_, i, &c);
      if (n == 0) {
        char byte[8];
        std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(text_[i]));
        Fail(i, std::string("the byte ") + byte + " is not UTF-8; save the file as UTF-8");
      }
      if (!AllowedCharacter(c)) {
        char code[16];
        std::snprintf(code, sizeof code, "U+%04X", static_cast<unsigned>(c));
        Fail(i, std::string("the control character ") + code + " is not allowed in XML");
      }
      i += n;
    }
  }

  // `&...;` at `i`: a predefined entity or a character reference; returns
  // the index after the ';'.
  std::size_t CheckReference(std::size_t i) const {
    const std::size_t semicolon = text_.find(';', i);
    const std::size_t end = semicolon == std::string::npos ? text_.size() : semicolon;
    const std::string name = text_.substr(i + 1, std::min<std::size_t>(end - i - 1, 32));
    const char* expected =
        "; expected &amp; &lt; &gt; &quot; &apos; or a character reference such as &#955; (write & as &amp;)";
    if (semicolon == std::string::npos || semicolon - i > 12) Fail(i, "an '&' that starts no reference" + std::string(expected));
    for (const char* entity : {"amp", "lt", "gt", "quot", "apos"})
      if (name == entity) return semicolon + 1;
    if (name.size() >= 2 && name[0] == '#') {
      const bool hex = name[1] == 'x';
      const std::string digits = name.substr(hex ? 2 : 1);
      std::uint32_t code = 0;
      bool ok = !digits.empty() && digits.size() <= 8;
      for (const char d : digits) {
        int v = -1;
        if (d >= '0' && d <= '9') v = d - '0';
        if (hex && d >= 'a' && d <= 'f') v = d - 'a' + 10;
        if (hex && d >= 'A' && d <= 'F') v = d - 'A' + 10;
        if (v < 0) ok = false;
        code = code * (hex ? 16 : 10) + static_cast<std::uint32_t>(std::max(v, 0));
      }
      if (!ok) Fail(i, "the character reference '&" + blocks::Excerpt(name) + ";' is not a number");
      if (!AllowedCharacter(code))
        Fail(i, "the character reference '&" + blocks::Excerpt(name) + ";' names a character XML does not allow");
      return semicolon + 1;
    }
    Fail(i, "the undefined entity '&" + blocks::Excerpt(name) + ";'" + expected);
  }

  const std::string& text_;
  const std::string& file_;
};

}  // namespace

void CheckXmlText(const std::string& text, const std::string& file) { TextChecker(text, file).Run(); }

}  // namespace mechflow::diagrams
