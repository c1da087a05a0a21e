#pragma once
// DiagramDescription: a diagram file as plain data, before anything is built.
//
// The XML reader fills it after checking the file's shape (known elements and
// attributes only); every item keeps the file:line it came from so that the
// loader, which evaluates and builds later, can still point at the source.

#include <string>
#include <vector>

namespace mechflow::diagrams {

struct SourceLoc {
  std::string file;
  int line = 0;
  // "file:line", the prefix of every message about this item.
  std::string str() const { return file + ":" + std::to_string(line); }
};

// An attribute as written, with its own location.
struct Attribute {
  std::string name;
  std::string value;
  SourceLoc loc;
};

// The attribute called `name` in `attributes`, or null.
inline const Attribute* FindAttribute(const std::vector<Attribute>& attributes, const std::string& name) {
  for (const Attribute& a : attributes)
    if (a.name == name) return &a;
  return nullptr;
}

struct IdentifierDesc {
  std::string name, value, comment, unit;
  SourceLoc loc;
};

struct BlockDesc {
  std::string type, name;
  std::vector<Attribute> params;  // every attribute except type and name
  SourceLoc loc;
  std::string text;    // the element's text content (CDATA included), as written
  SourceLoc text_loc;  // where that text starts
};

struct ConnectionDesc {
  std::string from, to;
  SourceLoc loc;
};

struct LogDesc {
  std::string signal, group, label, unit;
  SourceLoc loc;
};

// <report peak|min|peak_abs="signal" label=... unit=... index=...>: checked
// by the loader, which resolves the signal.
struct ReportDesc {
  std::vector<Attribute> attributes;
  SourceLoc loc;
};

// An XML element as written (mechanism content): tag, attributes, children.
struct ElementDesc {
  std::string tag;
  std::vector<Attribute> attributes;
  std::vector<ElementDesc> children;
  SourceLoc loc;

  const Attribute* Find(const std::string& name) const { return FindAttribute(attributes, name); }
  std::string Text(const std::string& name, const std::string& fallback = "") const {
    const Attribute* a = Find(name);
    return a ? a->value : fallback;
  }
};

// A named set of identifier values (a variant of a macro-command,
// ELEMENTS.md 1.2), selected with `mechflow run --variant NAME`.
struct VariantDesc {
  std::string group;  // <variants name=...>
  std::string name;
  std::vector<Attribute> assignments;  // name = identifier, value = its text
  SourceLoc loc;
};

// <script src="file.lua"/> or <script>code</script>: the control script.
struct ScriptDesc {
  std::string code;        // inline code is padded with newlines so that its
  std::string chunk_name;  // lines are the XML file's: "@file" for both forms
  SourceLoc loc;
  bool present() const { return !chunk_name.empty(); }
};

struct DiagramDescription {
  std::string name;     // <diagram name=...>, default: the file's stem
  std::string comment;
  std::string file;     // the path it was read from
  std::vector<IdentifierDesc> identifiers;
  std::vector<VariantDesc> variants;
  std::vector<ElementDesc> mechanisms;  // <mechanism>, with src= files read in
  std::vector<BlockDesc> blocks;
  std::vector<ConnectionDesc> connections;
  std::vector<Attribute> solver;  // attributes of <solver>
  SourceLoc solver_loc;
  std::vector<Attribute> output;  // attributes of <output>
  SourceLoc output_loc;
  std::vector<LogDesc> logs;
  std::vector<ReportDesc> reports;
  std::vector<ReportDesc> spectra;   // <spectrum>: attributes as written
  std::vector<ReportDesc> xy_plots;  // <xy>: attributes as written
  ScriptDesc script;
};

}  // namespace mechflow::diagrams
