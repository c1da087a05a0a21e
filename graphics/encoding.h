#pragma once
// Text encodings of the files graphics writes: JSON string literals and
// base64 of binary arrays.

#include <cstddef>
#include <string>

namespace mechflow::graphics {

// A JSON string literal: quotes, backslashes and control characters escaped.
std::string Quoted(const std::string& s);

// Standard base64 (RFC 4648) of `size` bytes.
std::string Base64(const void* data, std::size_t size);

}  // namespace mechflow::graphics
