#include "cli/help_topics.h"

#include <cstdlib>
#include <memory>

#include "blocks/framework/block_factory.h"
#include "blocks/support/suggest.h"
#include "diagrams/element_table.h"
#include "diagrams/evaluator.h"
#include "diagrams/loader.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"

namespace mechflow::cli {
namespace {

// Every block type, the standard library and the scripting blocks; those
// need a Lua state and identifiers to be registered, not to be described.
struct Registry {
  scripting::LuaState lua{scripting::LuaState::Options{}};
  scripting::IdentifierTable identifiers;
  blocks::BlockRegistry types;
  Registry() { diagrams::RegisterAllBlocks(&types, &lua, &identifiers); }
};

const Registry& Blocks() {
  static const Registry registry;
  return registry;
}

bool ParseNumbers(const std::string& text, std::vector<double>* out) {
  for (const std::string& item : diagrams::Split(text, " \t,")) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (end != item.c_str() + item.size()) return false;
    out->push_back(v);
  }
  return !out->empty();
}

// The type built with its defaults (and 1 for a required number), for its
// ports; null when a parameter has nothing to build it with (a table, a
// file, code: its ports depend on what is given).
std::unique_ptr<blocks::Block> WithDefaults(const blocks::BlockType& type) {
  if (type.takes_text) return nullptr;
  blocks::BlockParams params;
  for (const blocks::ParamSpec& p : type.params) {
    const bool number = p.kind == blocks::ParamKind::kNumber || p.kind == blocks::ParamKind::kNumbers;
    const std::string text = !p.default_value.empty() ? p.default_value : p.required && number ? "1" : "";
    if (text.empty()) {
      if (p.required) return nullptr;
      continue;
    }
    std::vector<double> numbers;
    switch (p.kind) {
      case blocks::ParamKind::kNumber:
      case blocks::ParamKind::kNumbers:
        if (!ParseNumbers(text, &numbers)) return nullptr;
        params.SetNumbers(p.name, numbers);
        break;
      case blocks::ParamKind::kTable: {
        std::vector<std::vector<double>> rows;
        for (const std::string& row : diagrams::Split(p.default_value, ";")) {
          if (!ParseNumbers(row, &numbers)) return nullptr;
          rows.push_back(std::move(numbers));
          numbers.clear();
        }
        params.SetTable(p.name, rows);
        break;
      }
      case blocks::ParamKind::kText:
        params.SetText(p.name, p.default_value);
        break;
      case blocks::ParamKind::kPath:
        return nullptr;
    }
  }
  try {
    return type.create("help", params);
  } catch (const std::exception&) {
    return nullptr;
  }
}

std::string Ports(const char* what, const std::vector<blocks::PortSpec>& ports) {
  std::string out = std::string(what) + ":";
  if (ports.empty()) out += " none";
  for (const blocks::PortSpec& p : ports) out += " " + p.name + (p.width == 1 ? "" : "[" + std::to_string(p.width) + "]");
  return out + "\n";
}

std::string BlockHelp(const blocks::BlockType& type) {
  std::string out = "block type " + type.name + ": " + type.doc + "\n\n";
  if (const std::unique_ptr<blocks::Block> block = WithDefaults(type)) {
    std::vector<blocks::PortSpec> inputs, outputs;
    for (int i = 0; i < block->num_inputs(); ++i) inputs.push_back(block->input_port(i));
    for (int i = 0; i < block->num_outputs(); ++i) outputs.push_back(block->output_port(i));
    out += "ports (as the defaults give them; [n]: width n)\n  " + Ports("inputs", inputs) + "  " + Ports("outputs", outputs);
  } else {
    out += "ports: they follow its parameters (mechflow check prints a diagram's)\n";
  }
  out += "\nparameters (attributes of <block type=\"" + type.name + "\" name=\"...\">):\n";
  if (type.params.empty()) out += "  none\n";
  for (const blocks::ParamSpec& p : type.params) {
    std::string line = "  " + p.name;
    line.resize(std::max<std::size_t>(line.size() + 1, 22), ' ');
    out += line + "(" + (p.required ? "required" : p.default_value.empty() ? "optional" : "default " + p.default_value) +
           ") " + p.doc + "\n";
  }
  if (type.takes_text) out += "  (its text content is Lua code)\n";
  return out;
}

std::vector<std::string> ElementTags() {
  std::vector<std::string> tags;
  for (const diagrams::ElementSpec& spec : diagrams::ElementTable()) tags.push_back(spec.tag);
  return tags;
}

// `title` then the names, comma-separated, in lines of at most 80 columns.
std::string Wrapped(const std::string& title, const std::vector<std::string>& names) {
  std::string out = title + "\n ", line;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string item = " " + names[i] + (i + 1 < names.size() ? "," : "");
    if (line.size() + item.size() > 78) out += line + "\n ", line.clear();
    line += item;
  }
  return out + line + "\n";
}

}  // namespace

std::string TopicsText() {
  return "\n" + Wrapped("Block types (mechflow help TYPE):", Blocks().types.Names()) + "\n" +
         Wrapped("Diagram elements (mechflow help TAG):", ElementTags());
}

bool IsTypeTopic(const std::string& topic) {
  return Blocks().types.Find(topic) || diagrams::FindElementSpec(topic);
}

std::string TypeHelp(const std::string& topic) {
  std::string out;
  if (const blocks::BlockType* type = Blocks().types.Find(topic)) out += BlockHelp(*type);
  if (const diagrams::ElementSpec* spec = diagrams::FindElementSpec(topic))
    out += (out.empty() ? "" : "\n") + diagrams::ElementHelp(*spec);
  return out;
}

std::vector<std::string> TypeTopics() {
  std::vector<std::string> topics = Blocks().types.Names();
  for (const std::string& tag : ElementTags()) topics.push_back(tag);
  return topics;
}

}  // namespace mechflow::cli
