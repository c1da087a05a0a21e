#pragma once
// DiagramDescription: a diagram file as plain data, before anything is built.
//
// The XML reader fills it after checking the file's shape (known elements and
// attributes only); every item keeps the file:line it came from so that the
// loader, which evaluates and builds later, can still point at the source.

#include <string>
#include <utility>
#include <vector>

#include "blocks/support/input_file.h"

namespace mechflow::diagrams {

struct SourceLoc {
  std::string file;
  int line = 0;
  // Inside a subsystem or part: the instance and the lines that included it,
  // innermost first ("in s[2] (chain.xml:30)"); "" at the diagram's level.
  std::string context = {};
  // "file:line", the prefix of every message about this item, then the
  // instance it belongs to, as a traceback: "stage.xml:12: in s[2] (chain.xml:30)".
  std::string str() const { return file + ":" + std::to_string(line) + (context.empty() ? "" : ": " + context); }
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
  // type="subsystem": the <param name value> children (the values of the
  // subsystem's parameters, expressions in the including scope) and the key
  // of the file read in (DiagramDescription::components)
  std::vector<Attribute> args = {};
  std::string component = {};
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
  // <include part=...>: the key of the part's file (DiagramDescription::components)
  std::string component = {};

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

// <input name unit start comment> of a diagram: a value set from outside
// (a co-simulation's input), a signal source named `name`.
struct DiagramInputDesc {
  std::string name, unit, start, comment;
  SourceLoc loc;
};

// <parameter name default unit comment> of a subsystem or part: its interface.
struct ParameterDesc {
  std::string name, default_value, unit, comment;
  bool has_default = false;
  SourceLoc loc;
};

// <input name width> and <output name> of a subsystem.
struct PortDesc {
  std::string name;
  std::string width;  // "" for an output, or an input taking the width of its source
  SourceLoc loc;
};

// A file whose root is <subsystem> (signal blocks with ports) or <part>
// (mechanism elements with attach points), read once however often it is
// used; the loader makes its instances (diagrams/instances.h).
struct ComponentDesc {
  std::string kind;  // "subsystem" or "part"
  std::string name;
  std::string file;  // the path it was read from
  SourceLoc loc;     // of its root element
  std::vector<ParameterDesc> parameters;
  std::vector<IdentifierDesc> identifiers;  // local: visible only inside
  // subsystem
  std::vector<PortDesc> inputs, outputs;
  std::vector<ElementDesc> mechanisms;
  std::vector<BlockDesc> blocks;
  std::vector<ConnectionDesc> connections;
  // part: <attach name> points, and its elements (bodies, joints, forces,
  // contacts, sensors, shapes, includes of further parts)
  std::vector<Attribute> attach_points;  // name = the attach point, value unused
  std::vector<ElementDesc> elements;
};

// One instance of a subsystem or part, as flattening made it.
struct InstanceDesc {
  std::string path;       // "d[1]", "chain.s[2]"; a part's starts with its mechanism's block name
  std::string kind;       // "subsystem" or "part"
  std::string component;  // the file
  SourceLoc loc;          // the including line
};

struct DiagramDescription {
  std::string name;     // <diagram name=...>, default: the file's stem
  std::string comment;
  std::string file;     // the path it was read from
  std::vector<IdentifierDesc> identifiers;
  std::vector<DiagramInputDesc> inputs;  // top-level <input>s
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
  // every <subsystem> and <part> file the diagram uses, by the path read
  // (the reader fills it; the loader's flattening uses it)
  std::vector<ComponentDesc> components;
  // the files the reader read besides this one (<mechanism src>, <script
  // src>, subsystem and part files); the loader reads tables and Lua block
  // files later (LoadedDiagram::reads)
  std::vector<blocks::FileRead> files_read;
  // filled when the loader flattens: the instances (a tree by their paths)
  // and the names a subsystem's output port is reached by ("d[1].F" ->
  // "d[1].fr.F"): logs, reports and sim:get take either
  std::vector<InstanceDesc> instances;
  std::vector<std::pair<std::string, std::string>> signal_aliases;
  // a subsystem <input width=...>: the signal that feeds it must have that width
  struct InputWidth {
    std::string signal;
    int width = 1;
    SourceLoc loc;
  };
  std::vector<InputWidth> input_widths;

  const ComponentDesc* FindComponent(const std::string& file) const {
    for (const ComponentDesc& c : components)
      if (c.file == file) return &c;
    return nullptr;
  }
};

}  // namespace mechflow::diagrams
