#pragma once
// Input text quoted in a message. A diagram, table or Lua file may come from
// someone else: a quoted line may be a 60 MB line, hold terminal control
// sequences, or be the second line of a file the user did not mean to show.
// Every message that quotes what it read goes through Excerpt.

#include <cstddef>
#include <string>
#include <string_view>

namespace mechflow::blocks {

inline constexpr std::size_t kExcerptLength = 60;
// A path is quoted further: a folder deep in a build tree is longer than 60
// characters, and its end is the part that tells two paths apart.
inline constexpr std::size_t kPathExcerptLength = 400;

// `text` made safe to print: control characters, DEL and bytes that are not
// UTF-8 written as \xNN (the rest of UTF-8 as it is); cut after about
// `max_length` characters with "..." appended.
std::string Excerpt(std::string_view text, std::size_t max_length = kExcerptLength);

// The same for a message of several lines (a Lua error with its traceback):
// newlines and tabs are kept.
std::string MessageExcerpt(std::string_view text, std::size_t max_length);

// Without the UTF-8 byte-order mark spreadsheet programs put at the start of
// a text file (else the first line's first field is not a number).
std::string_view WithoutByteOrderMark(std::string_view text);

}  // namespace mechflow::blocks
