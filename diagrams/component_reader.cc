// Reading the subsystem and part files a diagram uses (<block
// type="subsystem" src=...>, <include part=...>): each file once, however
// often it is used; its instances are made by the loader
// (diagrams/instances.h).

#include <filesystem>

#include "diagrams/xml_element_reader.h"

namespace mechflow::diagrams::xml {
namespace {

// The content of a <subsystem> or <part> root element.
ComponentDesc ReadComponent(const Reader& r, const XMLElement* root, const std::string& kind) {
  r.CheckShape(root);
  ComponentDesc c;
  c.kind = kind;
  c.name = r.Text(root, "name");
  c.file = r.file();
  c.loc = r.Loc(root);
  for (const XMLElement* e = root->FirstChildElement("parameter"); e; e = e->NextSiblingElement("parameter")) {
    r.CheckShape(e);
    c.parameters.push_back({r.Text(e, "name"), r.Text(e, "default"), r.Text(e, "unit"), r.Text(e, "comment"),
                            e->Attribute("default") != nullptr, r.Loc(e)});
  }
  if (kind == "subsystem") {
    for (const XMLElement* e = root->FirstChildElement(); e; e = e->NextSiblingElement()) {
      const std::string tag = e->Name();
      if (tag == "input" || tag == "output") {
        r.CheckShape(e, "subsystem " + tag);
        (tag == "input" ? c.inputs : c.outputs).push_back({r.Text(e, "name"), r.Text(e, "width"), r.Loc(e)});
      } else if (tag != "mechanism" && tag != "parameter") {
        r.CheckShape(e);
        for (const XMLElement* item = e->FirstChildElement(); item; item = item->NextSiblingElement())
          r.CheckShape(item);
      }
    }
    r.ReadContent(root, &c.identifiers, &c.mechanisms, &c.blocks, &c.connections);
  } else {
    for (const XMLElement* e = root->FirstChildElement(); e; e = e->NextSiblingElement()) {
      const std::string tag = e->Name();
      if (tag == "parameter") continue;
      if (tag == "attach") {
        r.CheckShape(e);
        c.attach_points.push_back({r.Text(e, "name"), "", r.Loc(e)});
      } else {
        c.elements.push_back(r.ReadTree(e));
      }
    }
  }
  return c;
}

}  // namespace

std::string Reader::ReadComponentFile(const XMLElement* e, const char* attribute, const std::string& kind) const {
  const std::string what = "<" + std::string(e->Name()) + "> '" + Text(e, "name") + "'";
  const char* src = e->Attribute(attribute);
  if (!src || !*src) Fail(e, what + " needs " + attribute + "=\"FILE.xml\", the " + kind + "'s file");
  // beside the naming file, else in the first --library folder that has it
  namespace fs = std::filesystem;
  std::string folder = fs::path(file_).parent_path().string();
  if (fs::path(src).is_relative() && !fs::exists(fs::path(folder) / src) && !session_.library.empty()) {
    std::vector<std::string> looked = {(fs::path(folder) / src).string()};
    const auto found = std::find_if(session_.library.begin(), session_.library.end(), [&](const std::string& library) {
      looked.push_back((fs::path(library) / src).string());
      return fs::exists(fs::path(library) / src);
    });
    if (found == session_.library.end())
      Fail(e, what + ": " + kind + " file '" + src + "' not found beside " + file_ + " nor in a --library folder (looked for " +
                  blocks::JoinNames(looked) + ")");
    folder = *found;
  }
  const blocks::NamedFile file = blocks::ReadNamedFile(src, folder, session_.reads, Loc(e).str() + ": " + kind);
  const std::string key = fs::path(file.path).lexically_normal().string();
  std::vector<std::string>& chain = session_.chain;
  if (std::find(chain.begin(), chain.end(), key) != chain.end()) {
    std::string cycle;
    for (auto it = std::find(chain.begin(), chain.end(), key); it != chain.end(); ++it) cycle += *it + " -> ";
    Fail(e, what + " includes " + key + ", which is being read: a cycle (" + cycle + key + ")");
  }
  if (static_cast<int>(chain.size()) > ReadSession::kMaxIncludeDepth)
    Fail(e, what + ": subsystems and parts nest more than " + std::to_string(ReadSession::kMaxIncludeDepth) +
                " levels deep");
  for (const ComponentDesc& c : *session_.components)
    if (c.file == key) {
      if (c.kind != kind) Fail(e, what + ": " + key + " holds a <" + c.kind + ">; expected a <" + kind + ">");
      return key;
    }
  tinyxml2::XMLDocument doc;
  ParseText(&doc, file.text, key);
  const XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != kind)
    throw InputError(key + ":" + std::to_string(root ? root->GetLineNum() : 1) + ": a " + kind +
                     " file holds one <" + kind + "> element (used by " + Loc(e).str() + ")");
  chain.push_back(key);
  ComponentDesc c;
  try {
    c = ReadComponent(Reader(key, session_), root, kind);
  } catch (const InputError& error) {
    // the including line, as a traceback (the instances are made later)
    std::string message = error.what();
    if (message.find(" (included at ") != std::string::npos && message.back() == ')') {
      message.back() = ',';
      throw InputError(message + " " + Loc(e).str() + ")");
    }
    throw InputError(message + " (included at " + Loc(e).str() + ")");
  }
  chain.pop_back();
  session_.components->push_back(std::move(c));
  return key;
}

}  // namespace mechflow::diagrams::xml
