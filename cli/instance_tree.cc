#include "cli/instance_tree.h"

#include <functional>

namespace mechflow::cli {

InstanceTree::InstanceTree(std::vector<std::string> paths)
    : paths_(std::move(paths)), children_(paths_.size()) {
  for (int i = 0; i < static_cast<int>(paths_.size()); ++i) index_.emplace(paths_[i], i);
  for (int i = 0; i < static_cast<int>(paths_.size()); ++i) {
    const int parent = Enclosing(paths_[i]);
    (parent < 0 ? roots_ : children_[parent]).push_back(i);
  }
}

int InstanceTree::Enclosing(std::string_view name) const {
  for (auto dot = name.rfind('.'); dot != std::string_view::npos && dot > 0; dot = name.rfind('.', dot - 1)) {
    const auto it = index_.find(name.substr(0, dot));
    if (it != index_.end()) return it->second;
  }
  return -1;
}

void PrintInstanceTree(const std::vector<diagrams::InstanceDesc>& instances, std::ostream& out) {
  if (instances.empty()) return;
  std::vector<std::string> paths;
  for (const diagrams::InstanceDesc& instance : instances) paths.push_back(instance.path);
  const InstanceTree tree(std::move(paths));
  out << "\ninstances:\n";
  const std::function<void(int, int)> print = [&](int i, int depth) {
    const diagrams::InstanceDesc& instance = instances[i];
    out << std::string(2 * depth + 2, ' ') << instance.path << "  " << instance.kind << " " << instance.component
        << "  (included at " << instance.loc.file << ":" << instance.loc.line << ")\n";
    for (const int child : tree.children(i)) print(child, depth + 1);
  };
  for (const int root : tree.roots()) print(root, 0);
}

}  // namespace mechflow::cli
