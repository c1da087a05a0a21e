// Variants (named sets of identifier values, ELEMENTS.md 1.2): applied in
// order, then --set; derived identifiers refused; unknown names suggested.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace mechflow {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kDiagram =
    "<diagram>\n"
    "<identifiers><identifier name=\"a\" value=\"1\"/><identifier name=\"b\" value=\"2*a\"/></identifiers>\n"
    "<variants name=\"Type\">\n"
    "  <variant name=\"Big\"><set identifier=\"a\" value=\"10\"/></variant>\n"
    "  <variant name=\"Huge\"><set identifier=\"a\" value=\"100\"/></variant>\n"
    "  <variant name=\"Bad\"><set identifier=\"b\" value=\"5\"/></variant>\n"
    "</variants>\n"
    "<variants name=\"Other\"><variant name=\"Big\"><set identifier=\"a\" value=\"7\"/></variant></variants>\n"
    "<blocks><block type=\"constant\" name=\"c\" value=\"b\"/></blocks>\n"
    "</diagram>\n";

double B(const std::vector<std::string>& variants, const std::vector<std::pair<std::string, double>>& sets = {}) {
  diagrams::LoadOptions options;
  options.variants = variants;
  options.overrides = sets;
  return testing::LoadXml(kDiagram, options).identifiers->Value("b");
}

TEST(VariantsTest, AppliedInOrderThenSetAndDerivedFollow) {
  EXPECT_EQ(B({}), 2);
  EXPECT_EQ(B({"Type/Big"}), 20);
  EXPECT_EQ(B({"Type/Big", "Huge"}), 200);
  EXPECT_EQ(B({"Huge", "Type/Big"}), 20);
  EXPECT_EQ(B({"Huge"}, {{"a", 3}}), 6);
  EXPECT_EQ(B({"Other/Big"}), 14);
}

TEST(VariantsTest, BadSelectionsAreInputErrors) {
  auto error = [](const std::vector<std::string>& variants) {
    return testing::InputErrorOf([&] { B(variants); });
  };
  EXPECT_THAT(error({"Hug"}), AllOf(StartsWith("--variant Hug: test.xml has no such variant (did you mean 'Huge'?)"),
                                    HasSubstr("variants: Big, Huge, Bad, Big")));
  EXPECT_THAT(error({"Big"}), AllOf(StartsWith("--variant Big: ambiguous (test.xml:4 and test.xml:8)"),
                                    HasSubstr("'Type/Big'")));
  EXPECT_THAT(error({"Bad"}), StartsWith("test.xml:6: variant 'Bad': "));
}

}  // namespace
}  // namespace mechflow
