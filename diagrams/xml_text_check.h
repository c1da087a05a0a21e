#pragma once
// The checks tinyxml2 leaves to us, made on a diagram file's text before it
// is parsed. tinyxml2 passes an undefined entity (`&foo;`) through as text,
// ignores a DOCTYPE (whose internal entities would then be silently not
// expanded) and does not check the encoding; mechflow refuses all three, so
// a file means what it says or is an error at its line:
//   - the text is UTF-8 (no overlong forms, surrogates or code points above
//     U+10FFFF), without control characters other than tab, newline and
//     carriage return (XML 1.0 allows no others);
//   - no DOCTYPE declaration;
//   - `&` starts one of the five predefined entities (&amp; &lt; &gt; &quot;
//     &apos;) or a character reference (&#N; &#xH;) naming a character XML
//     allows.
// Comments, CDATA sections and processing instructions are checked for
// encoding and control characters only.

#include <string>

namespace mechflow::diagrams {

// Throws InputError "file:line: ..." at the first violation.
void CheckXmlText(const std::string& text, const std::string& file);

}  // namespace mechflow::diagrams
