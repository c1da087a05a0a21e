#include "fmi/packed_settings.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "mech/errors.h"
#include "scripting/identifiers.h"

namespace mechflow::fmi {

std::string PackedSettings::Text() const {
  std::ostringstream out;
  out << "diagram " << diagram << "\n";
  for (const std::string& v : variants) out << "variant " << v << "\n";
  char number[32];
  for (const auto& [name, value] : overrides) {
    std::snprintf(number, sizeof number, "%.17g", value);
    out << "set " << name << "=" << number << "\n";
  }
  for (const auto& [name, text] : expression_overrides) out << "set-expression " << name << "=" << text << "\n";
  for (const std::string& l : library) out << "library " << l << "\n";
  if (!guid.empty()) out << "guid " << guid << "\n";
  return out.str();
}

PackedSettings PackedSettings::Parse(const std::string& text, const std::string& file) {
  PackedSettings s;
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const std::size_t space = line.find(' ');
    const std::string key = line.substr(0, space), rest = space == std::string::npos ? "" : line.substr(space + 1);
    const std::size_t eq = rest.find('=');
    const std::string where = file + ":" + std::to_string(n) + ": ";
    if (key == "diagram") s.diagram = rest;
    else if (key == "variant") s.variants.push_back(rest);
    else if (key == "guid") s.guid = rest;
    else if (key == "library") s.library.push_back(rest);
    else if ((key == "set" || key == "set-expression") && eq != std::string::npos) {
      if (key == "set-expression") {
        s.expression_overrides.emplace_back(rest.substr(0, eq), rest.substr(eq + 1));
        continue;
      }
      double value = 0.0;
      if (!scripting::ParseNumber(rest.substr(eq + 1), &value))
        throw InputError(where + "'" + rest + "': expected set NAME=NUMBER");
      s.overrides.emplace_back(rest.substr(0, eq), value);
    } else {
      throw InputError(where + "'" + line + "': expected diagram, variant, set, set-expression, library or guid");
    }
  }
  if (s.diagram.empty()) throw InputError(file + ":1: names no diagram (a line 'diagram FILE')");
  return s;
}

run::LoadOptions PackedSettings::Options(const std::string& resources) const {
  run::LoadOptions options;  // the sandbox on
  options.variants = variants;
  options.overrides = overrides;
  options.expression_overrides = expression_overrides;
  options.allow_read = {resources};
  for (const std::string& l : library) options.library.push_back((std::filesystem::path(resources) / l).string());
  return options;
}

std::string GuidOf(const std::string& text) {
  // two 64-bit FNV-1a hashes from different offsets: 128 bits
  std::uint64_t h[2] = {14695981039346656037ull, 1099511628211ull * 7919ull};
  for (std::uint64_t& part : h)
    for (const char c : text) {
      part ^= static_cast<unsigned char>(c);
      part *= 1099511628211ull;
    }
  char out[40];
  std::snprintf(out, sizeof out, "{%08x-%04x-%04x-%04x-%012llx}", static_cast<unsigned>(h[0] >> 32),
                static_cast<unsigned>((h[0] >> 16) & 0xffff), static_cast<unsigned>(h[0] & 0xffff),
                static_cast<unsigned>(h[1] >> 48), static_cast<unsigned long long>(h[1] & 0xffffffffffffull));
  return out;
}

}  // namespace mechflow::fmi
