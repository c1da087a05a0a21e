#pragma once
// The element reader the diagram, subsystem and part readers share
// (diagrams/xml_reader.cc, component_reader.cc): shapes checked against the
// element table, attributes with their file:line, and the session that
// reads each subsystem or part file once.

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <tinyxml2.h>

#include "blocks/support/excerpt.h"
#include "blocks/support/input_file.h"
#include "blocks/support/suggest.h"
#include "diagrams/description.h"
#include "diagrams/element_table.h"
#include "mech/errors.h"

namespace mechflow::diagrams::xml {

using tinyxml2::XMLAttribute;
using tinyxml2::XMLElement;

// What reading one diagram shares across its files: where files may be
// read from, the folders parts are looked up in (--library), the subsystem
// and part files read so far, and the chain of files being read (a cycle
// or a chain deeper than kMaxIncludeDepth is bad input).
struct ReadSession {
  static constexpr int kMaxIncludeDepth = 32;
  const blocks::ReadPolicy& reads;
  std::vector<std::string> library;
  std::vector<ComponentDesc>* components;
  std::vector<std::string> chain;  // files being read, the diagram first
};

// Parses `text` (a whole file) into `doc`; InputError "file:line: ..." when
// it is no well-formed XML or holds two top elements.
void ParseText(tinyxml2::XMLDocument* doc, const std::string& text, const std::string& file);

class Reader {
 public:
  Reader(std::string file, ReadSession& session) : file_(std::move(file)), session_(session) {}

  const std::string& file() const { return file_; }
  ReadSession& session() const { return session_; }

  SourceLoc Loc(const XMLElement* e) const { return {file_, e->GetLineNum()}; }

  [[noreturn]] void Fail(const XMLElement* e, const std::string& what) const {
    throw InputError(Loc(e).str() + ": " + what);
  }

  // Checks the attributes and children of `e` against the element table
  // (diagrams/element_table.h): for a typed element, its type's attributes.
  // `tag`: the table's name for it when that is not its own ("subsystem
  // input" for a subsystem file's <input>).
  void CheckShape(const XMLElement* e, const std::string& tag = "") const {
    const ElementSpec* spec = FindElementSpec(tag.empty() ? e->Name() : tag);
    if (!spec) throw std::logic_error(std::string("no table entry for element ") + e->Name());
    for (const XMLAttribute* a = e->FirstAttribute(); a; a = a->Next()) CheckNameText(e, a->Name(), a->Value());
    CheckAttributes(spec->tag, Attributes(e), Loc(e));
    const std::vector<std::string> children = spec->AllChildren();
    for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string name = c->Name();
      if (std::find(children.begin(), children.end(), name) != children.end()) continue;
      Fail(c, "unknown element <" + blocks::Excerpt(name) + "> inside <" + e->Name() + ">" +
                  blocks::DidYouMean(name, children) +
                  (children.empty() ? "; <" + std::string(e->Name()) + "> has no child elements"
                                    : "; expected one of: " + blocks::JoinNames(children)));
    }
  }

  // Names, labels and file names end up in CSV headers, plot scripts and
  // file names: none may hold a line break or other control character
  // (written as a character reference, the XML check lets them through).
  void CheckNameText(const XMLElement* e, const std::string& attribute, const char* value) const {
    static const char* kNameAttributes[] = {"name",   "label", "group", "unit", "csv",  "plot",
                                            "signal", "from",  "to",    "type", "identifier"};
    if (std::find_if(std::begin(kNameAttributes), std::end(kNameAttributes),
                     [&](const char* n) { return attribute == n; }) == std::end(kNameAttributes))
      return;
    for (const char* c = value; *c; ++c)
      if (static_cast<unsigned char>(*c) < 0x20 || *c == 0x7f)
        Fail(e, "<" + std::string(e->Name()) + "> " + attribute +
                    "= holds a line break or another control character; names, labels and file names may not");
  }

  std::string Text(const XMLElement* e, const char* attribute) const {
    const char* v = e->Attribute(attribute);
    return v ? v : "";
  }

  std::vector<Attribute> Attributes(const XMLElement* e, const std::vector<std::string>& skip = {}) const {
    std::vector<Attribute> out;
    for (const XMLAttribute* a = e->FirstAttribute(); a; a = a->Next()) {
      if (std::find(skip.begin(), skip.end(), a->Name()) != skip.end()) continue;
      out.push_back({a->Name(), a->Value(), {file_, a->GetLineNum()}});
    }
    return out;
  }

  // The single child element `name` of `parent`, or null; a second one is an error.
  const XMLElement* Single(const XMLElement* parent, const char* name) const {
    const XMLElement* e = parent->FirstChildElement(name);
    if (e && e->NextSiblingElement(name))
      Fail(e->NextSiblingElement(name), "a second <" + std::string(name) + "> element; a diagram has at most one");
    return e;
  }

  // The element and its children, shapes checked all the way down; the
  // parts an <include> names are read in (component_reader.cc).
  ElementDesc ReadTree(const XMLElement* e) const {
    CheckShape(e);
    ElementDesc out{e->Name(), Attributes(e), {}, Loc(e)};
    for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement())
      out.children.push_back(ReadTree(c));
    if (out.tag == "include") out.component = ReadComponentFile(e, "part", "part");
    return out;
  }

  // The subsystem or part file `e`'s attribute `attribute` names, read into
  // the session's components once (component_reader.cc); its key.
  std::string ReadComponentFile(const XMLElement* e, const char* attribute, const std::string& kind) const;

  static int LeadingNewlines(const char* text) {
    int n = 0;
    for (; *text == ' ' || *text == '\t' || *text == '\r' || *text == '\n'; ++text) n += *text == '\n';
    return n;
  }

  // <block type=... name=...>: attributes, and text content (Lua code) with its line
  BlockDesc ReadBlock(const XMLElement* e) const {
    BlockDesc b{Text(e, "type"), Text(e, "name"), Attributes(e, {"type", "name"}), Loc(e), "", Loc(e)};
    for (const XMLElement* p = e->FirstChildElement("param"); p; p = p->NextSiblingElement("param")) {
      if (b.type != "subsystem")
        Fail(p, "<param> gives a subsystem's parameter; block '" + b.name + "' is a " + b.type +
                    ", whose parameters are attributes of <block>");
      CheckShape(p);
      b.args.push_back({Text(p, "name"), Text(p, "value"), Loc(p)});
    }
    if (b.type == "subsystem") b.component = ReadComponentFile(e, "src", "subsystem");
    for (const tinyxml2::XMLNode* n = e->FirstChild(); n; n = n->NextSibling()) {
      const tinyxml2::XMLText* text = n->ToText();
      if (!text) continue;
      // tinyxml2 numbers a text node by its first non-blank character
      if (b.text.empty())
        b.text_loc = {file_, text->GetLineNum() - (text->CData() ? 0 : LeadingNewlines(text->Value()))};
      b.text += text->Value();
    }
    return b;
  }

  // <mechanism name=... src="file"/>: the file's <mechanism> element (its own
  // file:line in messages); attributes given here override the file's.
  ElementDesc ReadMechanism(const XMLElement* e) const;
  ScriptDesc ReadScript(const XMLElement* e) const;

  // The <identifiers>, <blocks> and <connections> of a diagram or subsystem
  // (`root`), and its <mechanism>s.
  void ReadContent(const XMLElement* root, std::vector<IdentifierDesc>* identifiers,
                   std::vector<ElementDesc>* mechanisms, std::vector<BlockDesc>* blocks,
                   std::vector<ConnectionDesc>* connections) const {
    for (const XMLElement* m = root->FirstChildElement("mechanism"); m; m = m->NextSiblingElement("mechanism"))
      mechanisms->push_back(ReadMechanism(m));
    for (const XMLElement* g = root->FirstChildElement("identifiers"); g; g = g->NextSiblingElement("identifiers"))
      for (const XMLElement* e = g->FirstChildElement("identifier"); e; e = e->NextSiblingElement("identifier"))
        identifiers->push_back({Text(e, "name"), Text(e, "value"), Text(e, "comment"), Text(e, "unit"), Loc(e)});
    for (const XMLElement* g = root->FirstChildElement("blocks"); g; g = g->NextSiblingElement("blocks"))
      for (const XMLElement* e = g->FirstChildElement("block"); e; e = e->NextSiblingElement("block"))
        blocks->push_back(ReadBlock(e));
    for (const XMLElement* g = root->FirstChildElement("connections"); g; g = g->NextSiblingElement("connections"))
      for (const XMLElement* e = g->FirstChildElement("connect"); e; e = e->NextSiblingElement("connect"))
        connections->push_back({Text(e, "from"), Text(e, "to"), Loc(e)});
  }

  DiagramDescription Read(const tinyxml2::XMLDocument& doc) const {
    const XMLElement* root = doc.RootElement();
    if (!root) throw InputError(file_ + ":1: the file holds no XML element; expected <diagram>");
    if (std::string(root->Name()) != "diagram")
      Fail(root, "the top element is <" + blocks::Excerpt(root->Name()) + ">; expected <diagram>");
    CheckShape(root);
    DiagramDescription d;
    d.file = file_;
    d.name = Text(root, "name");
    if (d.name.empty()) d.name = std::filesystem::path(file_).stem().string();
    d.comment = Text(root, "comment");

    for (const XMLElement* group = root->FirstChildElement(); group; group = group->NextSiblingElement()) {
      if (std::string(group->Name()) == "mechanism") continue;
      if (std::string(group->Name()) == "input") {
        CheckShape(group, "diagram input");
        d.inputs.push_back({Text(group, "name"), Text(group, "unit"), group->Attribute("start") ? Text(group, "start") : "0", Text(group, "comment"),
                            Loc(group)});
        continue;
      }
      CheckShape(group);
      for (const XMLElement* e = group->FirstChildElement(); e; e = e->NextSiblingElement()) CheckShape(e);
    }
    ReadContent(root, &d.identifiers, &d.mechanisms, &d.blocks, &d.connections);
    for (const XMLElement* g = root->FirstChildElement("variants"); g; g = g->NextSiblingElement("variants"))
      for (const XMLElement* e = g->FirstChildElement("variant"); e; e = e->NextSiblingElement("variant")) {
        VariantDesc v{Text(g, "name"), Text(e, "name"), {}, Loc(e)};
        for (const XMLElement* a = e->FirstChildElement("set"); a; a = a->NextSiblingElement("set")) {
          CheckShape(a);
          v.assignments.push_back({Text(a, "identifier"), Text(a, "value"), Loc(a)});
        }
        d.variants.push_back(std::move(v));
      }
    if (const XMLElement* s = Single(root, "script")) d.script = ReadScript(s);
    if (const XMLElement* s = Single(root, "solver")) {
      d.solver = Attributes(s);
      d.solver_loc = Loc(s);
    } else {
      d.solver_loc = Loc(root);
    }
    if (const XMLElement* o = Single(root, "output")) {
      d.output = Attributes(o);
      d.output_loc = Loc(o);
      for (const XMLElement* e = o->FirstChildElement("log"); e; e = e->NextSiblingElement("log"))
        d.logs.push_back({Text(e, "signal"), Text(e, "group"), Text(e, "label"), Text(e, "unit"), Loc(e)});
      for (const XMLElement* e = o->FirstChildElement("report"); e; e = e->NextSiblingElement("report"))
        d.reports.push_back({Attributes(e), Loc(e)});
      for (const XMLElement* e = o->FirstChildElement("spectrum"); e; e = e->NextSiblingElement("spectrum"))
        d.spectra.push_back({Attributes(e), Loc(e)});
      for (const XMLElement* e = o->FirstChildElement("xy"); e; e = e->NextSiblingElement("xy"))
        d.xy_plots.push_back({Attributes(e), Loc(e)});
    } else {
      d.output_loc = Loc(root);
    }
    return d;
  }

 private:
  std::string file_;
  ReadSession& session_;
};

}  // namespace mechflow::diagrams::xml
