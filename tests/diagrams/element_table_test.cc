// The element table (diagrams/element_table.h) decides what every element
// takes: one small diagram per tag and type, generated from the table itself
// (a new type is covered without a new test), shows that an attribute the
// element does not take -- a made-up one, or one another type of the same tag
// takes (mu on a linear force) -- is refused at the element's file:line.
#include <map>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "diagrams/attribute_units.h"
#include "diagrams/element_table.h"
#include "diagrams/xml_reader.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

using diagrams::ElementSpec;
using diagrams::ElementVariant;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// The variant of `parent` that may hold `child` (null: any, or none needed).
const ElementVariant* VariantHolding(const ElementSpec& parent, const std::string& child) {
  for (const std::string& c : parent.children)
    if (c == child) return parent.variants.empty() ? nullptr : &parent.variants[0];
  for (const ElementVariant& v : parent.variants)
    for (const std::string& c : v.children)
      if (c == child) return &v;
  return nullptr;
}

// `<tag a="1" ...` with its required attributes (the selector set to `variant`).
std::string OpenTag(const ElementSpec& spec, const ElementVariant* variant, const std::string& extra) {
  std::string out = "<" + spec.tag;
  for (const diagrams::AttributeSpec& a : spec.attributes)
    if (a.required) out += " " + a.name + "=\"" + (a.name == spec.selector && variant ? variant->name : "1") + "\"";
  if (variant)
    for (const diagrams::AttributeSpec& a : variant->attributes)
      if (a.required) out += " " + a.name + "=\"1\"";
  return out + extra;
}

// The roots of subsystem and part files, and what only they hold: not
// part of a diagram file (tests/diagrams/instances_test.cc reads them).
bool OnlyInComponentFiles(const ElementSpec& spec) {
  if (spec.tag == "diagram") return false;
  if (spec.tag == "subsystem" || spec.tag == "part") return true;
  for (const ElementSpec& s : diagrams::ElementTable())
    if (s.tag != "subsystem" && s.tag != "part")
      for (const std::string& c : s.AllChildren())
        if (c == spec.tag) return false;
  return true;
}

// A diagram holding `spec` (as `variant`, with `extra` attributes) on the
// last line of its chain of parents from <diagram>; returns that line.
int DiagramWith(const ElementSpec& spec, const ElementVariant* variant, const std::string& extra, std::string* xml) {
  std::vector<const ElementSpec*> chain = {&spec};
  while (chain.front()->tag != "diagram") {
    const ElementSpec* parent = nullptr;
    for (const ElementSpec& s : diagrams::ElementTable())
      for (const std::string& c : s.AllChildren())
        if (c == chain.front()->tag && s.tag != chain.front()->tag && !OnlyInComponentFiles(s)) parent = &s;
    if (!parent) ADD_FAILURE() << "no element holds <" << chain.front()->tag << ">";
    if (!parent) return 0;
    chain.insert(chain.begin(), parent);
  }
  *xml = "";
  for (std::size_t i = 0; i + 1 < chain.size(); ++i)
    *xml += OpenTag(*chain[i], VariantHolding(*chain[i], chain[i + 1]->tag), "") + ">\n";
  *xml += OpenTag(spec, variant, extra) + "/>\n";
  for (std::size_t i = chain.size() - 1; i-- > 0;) *xml += "</" + chain[i]->tag + ">\n";
  return static_cast<int>(chain.size());
}

std::string ReadError(const std::string& xml) {
  return testing::InputErrorOf([&] { diagrams::ReadDiagramText(xml, "test.xml"); });
}

// Each tag, and each type of it, as the table lists them.
std::vector<std::pair<const ElementSpec*, const ElementVariant*>> EveryElementType() {
  std::vector<std::pair<const ElementSpec*, const ElementVariant*>> out;
  for (const ElementSpec& spec : diagrams::ElementTable()) {
    if (spec.variants.empty()) out.push_back({&spec, nullptr});
    for (const ElementVariant& v : spec.variants) out.push_back({&spec, &v});
  }
  return out;
}

TEST(ElementTableTest, AStrayAttributeIsRefusedOnEveryElementType) {
  int covered = 0;
  for (const auto& [spec, variant] : EveryElementType()) {
    if (spec->open_attributes) continue;  // <block>: its type's parameters, below
    if (OnlyInComponentFiles(*spec) || spec->tag.find(' ') != std::string::npos) continue;
    const std::string what = "<" + spec->tag + (variant ? " " + spec->selector + "=" + variant->name : "") + ">";
    std::string xml;
    const int line = DiagramWith(*spec, variant, " zz_stray=\"1\"", &xml);
    const std::string error = ReadError(xml);
    EXPECT_THAT(error, StartsWith("test.xml:" + std::to_string(line) + ": ")) << what << "\n" << xml;
    EXPECT_THAT(error, HasSubstr("zz_stray")) << what;
    EXPECT_THAT(error, HasSubstr(spec->tag)) << what;
    ++covered;
  }
  EXPECT_GT(covered, 60);  // every type of force, joint, contact, sensor, shape, <et>, and the tags
}

// The class of defect the table closes: an attribute of one type written on
// another (a friction coefficient on a linear spring) did nothing, silently.
TEST(ElementTableTest, AnAttributeOfAnotherTypeIsRefused) {
  int covered = 0;
  for (const auto& [spec, variant] : EveryElementType()) {
    if (!variant) continue;
    std::vector<std::string> own;
    for (const diagrams::AttributeSpec& a : variant->attributes) own.push_back(a.name);
    for (const diagrams::AttributeSpec& a : spec->attributes) own.push_back(a.name);
    for (const diagrams::AttributeSpec* other : spec->AllAttributes()) {
      if (std::find(own.begin(), own.end(), other->name) != own.end()) continue;
      std::string xml;
      const int line = DiagramWith(*spec, variant, " " + other->name + "=\"1\"", &xml);
      EXPECT_THAT(ReadError(xml), AllOf(StartsWith("test.xml:" + std::to_string(line) + ": "),
                                        HasSubstr("has no '" + other->name + "' (only " + spec->selector + "=")))
          << xml;
      ++covered;
    }
  }
  EXPECT_GT(covered, 100);
}

TEST(ElementTableTest, MessagesNameTheValidAttributesAndTheNearestOne) {
  std::string xml;
  const ElementSpec& force = *diagrams::FindElementSpec("force");
  const int line = DiagramWith(force, force.FindVariant("linear"), " mu=\"0.3\"", &xml);
  EXPECT_THAT(ReadError(xml), AllOf(StartsWith("test.xml:" + std::to_string(line) + ": force '1' attribute 'mu': "
                                               "a linear force has no 'mu' (only type=\"elastic_friction2\" takes it)"),
                                    HasSubstr("it takes c, x0, d, f0 and name, type")));
  DiagramWith(force, force.FindVariant("linear"), " cc=\"1\"", &xml);
  EXPECT_THAT(ReadError(xml), HasSubstr("has no 'cc' (did you mean 'c'?)"));
  const ElementSpec& solver = *diagrams::FindElementSpec("solver");
  DiagramWith(solver, nullptr, " t_ned=\"1\"", &xml);
  EXPECT_THAT(ReadError(xml), AllOf(HasSubstr("<solver> has no attribute 't_ned' (did you mean 't_end'?)"),
                                    HasSubstr("valid attributes: t_start, t_end")));
}

TEST(ElementTableTest, ABlockRefusesAParameterItsTypeDoesNotTake) {
  const std::string error = testing::InputErrorOf([] {
    testing::LoadXml("<diagram>\n<blocks>\n<block type=\"constant\" name=\"c\" value=\"1\"\n zz_stray=\"1\"/>\n"
                     "</blocks>\n</diagram>\n");
  });
  EXPECT_THAT(error, AllOf(StartsWith("test.xml:4: block 'c' (constant) has no parameter 'zz_stray'"),
                           HasSubstr("valid: type, name, value")));
}

// Units come from the same table: what unit checks read is what help prints.
TEST(ElementTableTest, UnitsAreTheTablesUnits) {
  EXPECT_EQ(diagrams::AttributeUnit("force", "linear", "c"), "N/m");
  EXPECT_EQ(diagrams::AttributeUnit("joint", "rotational", "q0"), "rad");
  EXPECT_EQ(diagrams::AttributeUnit("joint", "translational", "q0"), "m");
  EXPECT_EQ(diagrams::AttributeUnit("joint_force", "linear", "c"), "");  // N/m or N m/rad by its coordinate
  EXPECT_EQ(diagrams::AttributeUnit("solver", "", "t_end"), "s");
  for (const auto& [spec, variant] : EveryElementType())
    for (const diagrams::AttributeSpec* a : diagrams::AttributesOf(spec->tag, variant ? variant->name : ""))
      if (spec->selector == "type") {
        EXPECT_EQ(diagrams::AttributeUnit(spec->tag, variant ? variant->name : "", a->name), a->unit)
            << spec->tag << " " << a->name;
      }
}

}  // namespace
}  // namespace mechflow
