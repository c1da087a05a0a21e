// The standard registry: every block type of the library is there, each
// parameter is documented and has a usable default, and the block built with
// defaults only is well-formed.

#include <set>
#include <string>

#include <gtest/gtest.h>

#include "tests/blocks/block_test_util.h"

namespace mechflow::blocks {
namespace {

using testing::MakeBlock;
using testing::ParamTexts;
using testing::StandardRegistry;

// Values for the required parameters, so that every type can be built.
const ParamTexts& Required(const std::string& type) {
  static const std::map<std::string, ParamTexts> required = {
      {"constant", {{"value", "1"}}},
      {"gain", {{"k", "2"}}},
      {"saturation", {{"lower", "-1"}, {"upper", "1"}}},
      {"dead_zone", {{"start", "-1"}, {"end", "1"}}},
      {"first_order_lag", {{"time_constant", "1"}}},
      {"friction_from_normal_force", {{"mu_static", "0.5"}, {"mu_dynamic", "0.3"}}},
      {"sample_hold", {{"period", "1"}}},
      {"table", {{"points", "0 0; 1 1"}}},
      {"lookup", {{"points", "0 0; 1 1"}}},
      {"lookup_2d", {{"x", "0 1"}, {"y", "0 1"}, {"values", "0 1; 1 2"}}},
      {"motion_table", {{"points", "0 0; 1 1"}}},
      {"motion_filter", {{"frequency", "10"}}},
  };
  static const ParamTexts none;
  const auto it = required.find(type);
  return it == required.end() ? none : it->second;
}

TEST(RegistryTest, HoldsTheWholeLibrary) {
  const auto names = StandardRegistry().Names();
  const std::set<std::string> have(names.begin(), names.end());
  for (const char* type : {"constant", "clock", "step", "ramp", "sine", "table", "gain", "sum", "product", "abs",
                           "saturation", "dead_zone", "integrator", "first_order_lag", "friction_from_normal_force",
                           "recorder", "sample_hold", "lookup", "lookup_2d", "motion_sine", "motion_table",
                           "motion_filter"})
    EXPECT_TRUE(have.count(type)) << type;
  EXPECT_EQ(have.size(), 22u);
}

TEST(RegistryTest, EveryParameterIsDocumentedAndEveryTypeBuildsFromDefaults) {
  for (const std::string& name : StandardRegistry().Names()) {
    const BlockType& type = *StandardRegistry().Find(name);
    EXPECT_FALSE(type.doc.empty()) << name;
    for (const ParamSpec& p : type.params) {
      EXPECT_FALSE(p.doc.empty()) << name << "." << p.name;
      // a required parameter has no default, and only it needs a value
      if (p.required) {
        EXPECT_TRUE(p.default_value.empty()) << name << "." << p.name;
        EXPECT_TRUE(Required(name).count(p.name)) << name << "." << p.name;
      }
    }
    // the default texts read as numbers where numbers are expected
    const auto block = MakeBlock(name, "b", Required(name));
    EXPECT_EQ(block->type(), name);
    EXPECT_EQ(block->name(), "b");
  }
}

TEST(RegistryTest, WidthMakesElementwiseBlocksVectors) {
  for (const char* type : {"gain", "sum", "product", "abs", "saturation", "dead_zone", "integrator",
                           "first_order_lag", "sample_hold"}) {
    ParamTexts p = Required(type);
    p["width"] = "4";
    const auto block = MakeBlock(type, "b", p);
    for (int i = 0; i < block->num_inputs(); ++i) EXPECT_EQ(block->input_port(i).width, 4) << type;
    EXPECT_EQ(block->output_port(0).width, 4) << type;
  }
}

}  // namespace
}  // namespace mechflow::blocks
