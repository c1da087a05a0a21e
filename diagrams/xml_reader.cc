#include "diagrams/xml_reader.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <tinyxml2.h>

#include "blocks/support/excerpt.h"
#include "blocks/support/input_file.h"
#include "blocks/support/suggest.h"
#include "diagrams/element_table.h"
#include "diagrams/xml_text_check.h"
#include "mech/errors.h"

namespace mechflow::diagrams {
namespace {

using blocks::ReadInputFile;
using blocks::ReadNamedFile;
using blocks::ReadPolicy;

using tinyxml2::XMLAttribute;
using tinyxml2::XMLElement;

class Reader {
 public:
  Reader(std::string file, const ReadPolicy& reads) : file_(std::move(file)), reads_(reads) {}

  SourceLoc Loc(const XMLElement* e) const { return {file_, e->GetLineNum()}; }

  [[noreturn]] void Fail(const XMLElement* e, const std::string& what) const {
    throw InputError(Loc(e).str() + ": " + what);
  }

  // Checks the attributes and children of `e` against the element table
  // (diagrams/element_table.h): for a typed element, its type's attributes.
  void CheckShape(const XMLElement* e) const {
    const ElementSpec* spec = FindElementSpec(e->Name());
    if (!spec) throw std::logic_error(std::string("no table entry for element ") + e->Name());
    for (const XMLAttribute* a = e->FirstAttribute(); a; a = a->Next()) CheckNameText(e, a->Name(), a->Value());
    CheckAttributes(e->Name(), Attributes(e), Loc(e));
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

  // The element and its children, shapes checked all the way down.
  ElementDesc ReadTree(const XMLElement* e) const {
    CheckShape(e);
    ElementDesc out{e->Name(), Attributes(e), {}, Loc(e)};
    for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement())
      out.children.push_back(ReadTree(c));
    return out;
  }

  static int LeadingNewlines(const char* text) {
    int n = 0;
    for (; *text == ' ' || *text == '\t' || *text == '\r' || *text == '\n'; ++text) n += *text == '\n';
    return n;
  }

  // <block type=... name=...>: attributes, and text content (Lua code) with its line
  BlockDesc ReadBlock(const XMLElement* e) const {
    BlockDesc b{Text(e, "type"), Text(e, "name"), Attributes(e, {"type", "name"}), Loc(e), "", Loc(e)};
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

    for (const XMLElement* m = root->FirstChildElement("mechanism"); m; m = m->NextSiblingElement("mechanism"))
      d.mechanisms.push_back(ReadMechanism(m));
    for (const XMLElement* group = root->FirstChildElement(); group; group = group->NextSiblingElement()) {
      if (std::string(group->Name()) == "mechanism") continue;
      CheckShape(group);
      for (const XMLElement* e = group->FirstChildElement(); e; e = e->NextSiblingElement()) CheckShape(e);
    }
    for (const XMLElement* g = root->FirstChildElement("identifiers"); g; g = g->NextSiblingElement("identifiers"))
      for (const XMLElement* e = g->FirstChildElement("identifier"); e; e = e->NextSiblingElement("identifier"))
        d.identifiers.push_back({Text(e, "name"), Text(e, "value"), Text(e, "comment"), Text(e, "unit"), Loc(e)});
    for (const XMLElement* g = root->FirstChildElement("variants"); g; g = g->NextSiblingElement("variants"))
      for (const XMLElement* e = g->FirstChildElement("variant"); e; e = e->NextSiblingElement("variant")) {
        VariantDesc v{Text(g, "name"), Text(e, "name"), {}, Loc(e)};
        for (const XMLElement* a = e->FirstChildElement("set"); a; a = a->NextSiblingElement("set")) {
          CheckShape(a);
          v.assignments.push_back({Text(a, "identifier"), Text(a, "value"), Loc(a)});
        }
        d.variants.push_back(std::move(v));
      }
    for (const XMLElement* g = root->FirstChildElement("blocks"); g; g = g->NextSiblingElement("blocks"))
      for (const XMLElement* e = g->FirstChildElement("block"); e; e = e->NextSiblingElement("block"))
        d.blocks.push_back(ReadBlock(e));
    for (const XMLElement* g = root->FirstChildElement("connections"); g; g = g->NextSiblingElement("connections"))
      for (const XMLElement* e = g->FirstChildElement("connect"); e; e = e->NextSiblingElement("connect"))
        d.connections.push_back({Text(e, "from"), Text(e, "to"), Loc(e)});
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
  const ReadPolicy& reads_;  // where the files it names may be
};

tinyxml2::XMLError ParseText(tinyxml2::XMLDocument* doc, const std::string& text, const std::string& file) {
  CheckXmlText(text, file);
  if (doc->Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS) {
    throw InputError(file + ":" + std::to_string(doc->ErrorLineNum()) + ": malformed XML: " +
                     blocks::Excerpt(doc->ErrorStr() ? doc->ErrorStr() : doc->ErrorName(), 160));
  }
  if (const XMLElement* root = doc->RootElement(); root && root->NextSiblingElement())
    throw InputError(file + ":" + std::to_string(root->NextSiblingElement()->GetLineNum()) +
                     ": a second top-level element <" + blocks::Excerpt(root->NextSiblingElement()->Name()) +
                     ">; a file holds one <" + blocks::Excerpt(root->Name()) + "> element");
  return tinyxml2::XML_SUCCESS;
}


ElementDesc Reader::ReadMechanism(const XMLElement* e) const {
  const char* src = e->Attribute("src");
  if (!src) return ReadTree(e);
  CheckShape(e);
  if (e->FirstChildElement()) Fail(e, "<mechanism src=...> takes its content from the file; it has no children here");
  const blocks::NamedFile file =
      ReadNamedFile(src, std::filesystem::path(file_).parent_path().string(), reads_, Loc(e).str() + ": mechanism");
  const std::string& path = file.path;
  tinyxml2::XMLDocument doc;
  ParseText(&doc, file.text, path);
  const XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "mechanism")
    throw InputError(path + ":1: a mechanism file holds one <mechanism> element");
  ElementDesc m = Reader(path, reads_).ReadTree(root);
  for (const auto& a : Attributes(e, {"src"})) {
    bool replaced = false;
    for (auto& existing : m.attributes)
      if (existing.name == a.name) existing = a, replaced = true;
    if (!replaced) m.attributes.push_back(a);
  }
  return m;
}

ScriptDesc Reader::ReadScript(const XMLElement* e) const {
  ScriptDesc script;
  script.loc = Loc(e);
  const char* src = e->Attribute("src");
  const tinyxml2::XMLNode* text = e->FirstChild();
  const bool has_text =
      text && text->ToText() && std::string(text->Value()).find_first_not_of(" \t\r\n") != std::string::npos;
  if (src && has_text) Fail(e, "<script> has both src= and code; give one of them");
  if (src) {
    blocks::NamedFile file =
        ReadNamedFile(src, std::filesystem::path(file_).parent_path().string(), reads_, Loc(e).str() + ": script");
    script.code = std::move(file.text);
    script.chunk_name = "@" + file.path;
  } else if (has_text) {
    // Lua counts lines from the chunk's start: pad it so they are the file's.
    // tinyxml2 gives the line of the text's first non-blank character, but of
    // a CDATA section its start, where the code starts too.
    const std::string code = text->Value();
    const auto blank = code.substr(0, code.find_first_not_of(" \t\r\n"));
    const int first_line =
        text->GetLineNum() - (text->ToText()->CData() ? 0 : static_cast<int>(std::count(blank.begin(), blank.end(), '\n')));
    script.code = std::string(std::max(0, first_line - 1), '\n') + code;
    script.chunk_name = "@" + file_;
  } else {
    Fail(e, "<script> is empty; give src=\"file.lua\" or the code as its content");
  }
  return script;
}

}  // namespace

DiagramDescription ReadDiagramText(const std::string& text, const std::string& file,
                                   const std::vector<std::string>& allow_read) {
  const ReadPolicy reads(file, allow_read);
  tinyxml2::XMLDocument doc;
  ParseText(&doc, text, file);
  return Reader(file, reads).Read(doc);
}

DiagramDescription ReadDiagramFile(const std::string& path, const std::vector<std::string>& allow_read) {
  return ReadDiagramText(ReadInputFile(path, "diagram file"), path, allow_read);
}

}  // namespace mechflow::diagrams
