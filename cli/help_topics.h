#pragma once
// `mechflow help TYPE`: one block type's or diagram element's reference,
// read from the tables the loader checks diagrams against (the block
// registry's parameters, diagrams/element_table.h), so help and checks agree.

#include <string>
#include <vector>

namespace mechflow::cli {

// Block types and element tags, for the list of topics and did-you-mean.
std::vector<std::string> TypeTopics();
bool IsTypeTopic(const std::string& topic);
// Ports (blocks), attributes or parameters with units, defaults and meaning.
std::string TypeHelp(const std::string& topic);
// The block types and element tags, for `mechflow help`.
std::string TopicsText();

}  // namespace mechflow::cli
