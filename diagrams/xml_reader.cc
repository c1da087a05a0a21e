#include "diagrams/xml_reader.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <tinyxml2.h>

#include "diagrams/xml_element_reader.h"
#include "diagrams/xml_text_check.h"

namespace mechflow::diagrams {
namespace xml {

using blocks::ReadInputFile;
using blocks::ReadNamedFile;

namespace {

// What the parser found, in words, and what it names ("XMLElement
// name=sensor"), without its own error codes.
std::string ParseProblem(const tinyxml2::XMLDocument& doc) {
  std::string words;
  switch (doc.ErrorID()) {
    case tinyxml2::XML_ERROR_PARSING_ELEMENT:
      words = "an element that does not parse ('<' then a name, '>' at the end)";
      break;
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
      words = "an attribute that does not parse (name=\"value\", quoted, each name once)";
      break;
    case tinyxml2::XML_ERROR_PARSING_TEXT:
      words = "text that does not parse (write '<' as &lt; and '&' as &amp;)";
      break;
    case tinyxml2::XML_ERROR_PARSING_CDATA: words = "a <![CDATA[ section without its ]]>"; break;
    case tinyxml2::XML_ERROR_PARSING_COMMENT: words = "a comment without its -->"; break;
    case tinyxml2::XML_ERROR_PARSING_DECLARATION: words = "an <?xml ...?> declaration that does not parse"; break;
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT: words = "no element at all"; break;
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
      words = "an element not closed where it should be (an end tag for another element, or none)";
      break;
    default: words = doc.ErrorName(); break;
  }
  const std::string full = doc.ErrorStr() ? doc.ErrorStr() : "";
  const std::size_t at = full.find("Line number=");
  const std::size_t detail = at == std::string::npos ? std::string::npos : full.find(": ", at);
  if (detail != std::string::npos && detail + 2 < full.size()) words += " [" + full.substr(detail + 2) + "]";
  return words;
}

}  // namespace

void ParseText(tinyxml2::XMLDocument* doc, const std::string& text, const std::string& file) {
  CheckXmlText(text, file);
  if (doc->Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS)
    throw InputError(file + ":" + std::to_string(doc->ErrorLineNum()) + ": malformed XML: " +
                     blocks::Excerpt(ParseProblem(*doc), 200));
  if (const XMLElement* root = doc->RootElement(); root && root->NextSiblingElement())
    throw InputError(file + ":" + std::to_string(root->NextSiblingElement()->GetLineNum()) +
                     ": a second top-level element <" + blocks::Excerpt(root->NextSiblingElement()->Name()) +
                     ">; a file holds one <" + blocks::Excerpt(root->Name()) + "> element");
}


ElementDesc Reader::ReadMechanism(const XMLElement* e) const {
  const char* src = e->Attribute("src");
  if (!src) return ReadTree(e);
  CheckShape(e);
  if (e->FirstChildElement()) Fail(e, "<mechanism src=...> takes its content from the file; it has no children here");
  const blocks::NamedFile file =
      ReadNamedFile(src, std::filesystem::path(file_).parent_path().string(), session_.reads, Loc(e).str() + ": mechanism");
  const std::string& path = file.path;
  tinyxml2::XMLDocument doc;
  ParseText(&doc, file.text, path);
  const XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "mechanism")
    throw InputError(path + ":1: a mechanism file holds one <mechanism> element");
  ElementDesc m = Reader(path, session_).ReadTree(root);
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
        ReadNamedFile(src, std::filesystem::path(file_).parent_path().string(), session_.reads, Loc(e).str() + ": script");
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

}  // namespace xml

DiagramDescription ReadDiagramText(const std::string& text, const std::string& file,
                                   const std::vector<std::string>& allow_read,
                                   const std::vector<std::string>& library) {
  for (const std::string& folder : library)
    if (!std::filesystem::is_directory(folder))
      throw InputError("--library '" + blocks::Excerpt(folder, blocks::kPathExcerptLength) + "': no such folder");
  // folders parts are looked up in may be read from
  std::vector<std::string> readable = allow_read;
  readable.insert(readable.end(), library.begin(), library.end());
  const blocks::ReadPolicy reads(file, readable);
  std::vector<ComponentDesc> components;
  xml::ReadSession session{reads, library, &components, {file}};
  tinyxml2::XMLDocument doc;
  xml::ParseText(&doc, text, file);
  DiagramDescription d = xml::Reader(file, session).Read(doc);
  d.components = std::move(components);
  d.files_read = reads.files_read();
  return d;
}

DiagramDescription ReadDiagramFile(const std::string& path, const std::vector<std::string>& allow_read,
                                   const std::vector<std::string>& library) {
  return ReadDiagramText(blocks::ReadInputFile(path, "diagram file"), path, allow_read, library);
}

}  // namespace mechflow::diagrams
