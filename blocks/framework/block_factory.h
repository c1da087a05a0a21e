#pragma once
// BlockRegistry: block types by name, with the parameters each accepts.
//
// The XML loader checks a block's attributes against its type's ParamSpecs
// before anything is built (an unknown attribute is an error, a missing
// required one too), evaluates them (numbers or identifier expressions) into
// BlockParams, and calls the type's factory. Factories throw InputError for
// values that are well-formed but unusable (e.g. "period must be > 0"); the
// loader prefixes file:line and the block's name.

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

enum class ParamKind {
  kNumber,   // one number or expression
  kNumbers,  // a list: "1 2 3" or "1, 2, 3" (each item a number or an expression without spaces)
  kTable,    // rows separated by ';': "0 0; 1 2; 3 2"
  kText,     // taken as written (signs "+-", an expression, port names)
  kPath,     // a file name, resolved against the diagram's folder, read by the loader (blocks/support/input_file.h)
};

struct ParamSpec {
  std::string name;
  ParamKind kind = ParamKind::kNumber;
  bool required = false;
  std::string default_value;  // text as a user would write it; empty: none
  std::string doc;            // one line, with units
  // The SI unit an identifier given as the value is checked against
  // (diagrams/unit_check.h); "" where the unit depends on more.
  std::string unit = {};
};

// Evaluated parameter values of one block.
class BlockParams {
 public:
  bool Has(const std::string& name) const;
  double Number(const std::string& name) const;
  const std::vector<double>& Numbers(const std::string& name) const;
  const std::vector<std::vector<double>>& Table(const std::string& name) const;
  const std::string& Text(const std::string& name) const;  // kText, and kPath: the file's path
  const std::string& FileText(const std::string& name) const;  // kPath: the file's bytes

  void SetNumbers(const std::string& name, std::vector<double> values);
  void SetTable(const std::string& name, std::vector<std::vector<double>> rows);
  void SetText(const std::string& name, std::string text);
  void SetFile(const std::string& name, std::string path, std::string contents);

 private:
  std::map<std::string, std::vector<double>> numbers_;
  std::map<std::string, std::vector<std::vector<double>>> tables_;
  std::map<std::string, std::string> texts_;
  std::map<std::string, std::string> file_texts_;
};

struct BlockType {
  std::string name;
  std::string doc;  // one line: what it computes
  std::vector<ParamSpec> params;
  std::function<std::unique_ptr<Block>(const std::string& block_name, const BlockParams&)> create;
  // accepts the element's text content (code), passed as BlockParams texts
  // "#text", "#text_file" and number "#text_line" (the text's first line)
  bool takes_text = false;

  const ParamSpec* FindParam(const std::string& param) const;
};

class BlockRegistry {
 public:
  // Adds a type; a second type of the same name is a programming error.
  void Add(BlockType type);
  const BlockType* Find(const std::string& type_name) const;
  std::vector<std::string> Names() const;  // sorted

 private:
  std::map<std::string, BlockType> types_;
};

// Registers the standard library of blocks/library/.
void RegisterStandardBlocks(BlockRegistry* registry);

}  // namespace mechflow::blocks
