#include "blocks/framework/block_factory.h"

#include <stdexcept>

#include "mech/errors.h"

namespace mechflow::blocks {

bool BlockParams::Has(const std::string& name) const {
  return numbers_.count(name) || tables_.count(name) || texts_.count(name);
}

double BlockParams::Number(const std::string& name) const {
  const auto& v = Numbers(name);
  if (v.size() != 1)
    throw InputError("parameter '" + name + "' must be one number, got " + std::to_string(v.size()));
  return v[0];
}

const std::vector<double>& BlockParams::Numbers(const std::string& name) const {
  const auto it = numbers_.find(name);
  if (it == numbers_.end()) throw std::logic_error("parameter '" + name + "' was not given");
  return it->second;
}

const std::vector<std::vector<double>>& BlockParams::Table(const std::string& name) const {
  const auto it = tables_.find(name);
  if (it == tables_.end()) throw std::logic_error("parameter '" + name + "' was not given");
  return it->second;
}

const std::string& BlockParams::Text(const std::string& name) const {
  const auto it = texts_.find(name);
  if (it == texts_.end()) throw std::logic_error("parameter '" + name + "' was not given");
  return it->second;
}

const std::string& BlockParams::FileText(const std::string& name) const {
  const auto it = file_texts_.find(name);
  if (it == file_texts_.end()) throw std::logic_error("file parameter '" + name + "' was not read");
  return it->second;
}

void BlockParams::SetNumbers(const std::string& name, std::vector<double> values) {
  numbers_[name] = std::move(values);
}
void BlockParams::SetTable(const std::string& name, std::vector<std::vector<double>> rows) {
  tables_[name] = std::move(rows);
}
void BlockParams::SetText(const std::string& name, std::string text) { texts_[name] = std::move(text); }
void BlockParams::SetFile(const std::string& name, std::string path, std::string contents) {
  texts_[name] = std::move(path);
  file_texts_[name] = std::move(contents);
}

const ParamSpec* BlockType::FindParam(const std::string& param) const {
  for (const auto& p : params)
    if (p.name == param) return &p;
  return nullptr;
}

void BlockRegistry::Add(BlockType type) {
  const std::string name = type.name;
  if (!types_.emplace(name, std::move(type)).second)
    throw std::logic_error("block type '" + name + "' registered twice");
}

const BlockType* BlockRegistry::Find(const std::string& type_name) const {
  const auto it = types_.find(type_name);
  return it == types_.end() ? nullptr : &it->second;
}

std::vector<std::string> BlockRegistry::Names() const {
  std::vector<std::string> names;
  for (const auto& [name, type] : types_) names.push_back(name);
  return names;
}

}  // namespace mechflow::blocks
