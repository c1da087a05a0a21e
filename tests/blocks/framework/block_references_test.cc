// References to outputs and inputs when names are instance paths: block names
// with dots and indices ("d[1].fr"), port names with dots (a mechanism's
// sensor "s[2].x"), and signal aliases (a subsystem's output "d[1].F" standing
// for the inner "d[1].fr.F").

#include <memory>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "blocks/framework/diagram_builder.h"
#include "blocks/framework/evaluation.h"
#include "tests/blocks/block_test_util.h"

namespace mechflow::blocks::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// Constant outputs named like a mechanism's sensors: "s[0].x" = 1,
// "s[1].x" = 2, "y" = 3.
class Sensors : public Block {
 public:
  explicit Sensors(std::string name) : Block("sensors", std::move(name)) {
    for (const char* port : {"s[0].x", "s[1].x", "y"}) DeclareOutputPort(port);
  }

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override { ctx.output(port)[0] = port + 1.0; }
};

std::string BuildError(DiagramBuilder* b) {
  try {
    b->Build();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(built)";
}

std::string ResolveError(const Diagram& d, const std::string& reference) {
  try {
    d.ResolveSignal(reference);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(resolved)";
}

// The value a built diagram gives the reference, at its initial state.
double ValueOf(const Diagram& d, const std::string& reference) {
  std::vector<double> x;
  Context ctx = SettledContext(d, &x);
  EvaluateOutputs(d, &ctx);
  return ctx.signals[d.ResolveSignal(reference).offset];
}

TEST(BlockReferencesTest, BlockNamesMayBeInstancePaths) {
  DiagramBuilder b;
  b.AddBlock(MakeBlock("constant", "d[0].c", {{"value", "4"}}));
  b.AddBlock(MakeBlock("gain", "chain.s[2].gain", {{"k", "2"}}));
  b.Connect("d[0].c", "chain.s[2].gain.u");
  const auto d = b.Build();
  EXPECT_EQ(d->ResolveSignal("chain.s[2].gain.y").name, "chain.s[2].gain.y");
  EXPECT_EQ(d->ResolveSignal("chain.s[2].gain").name, "chain.s[2].gain.y");  // its one output
  EXPECT_EQ(ValueOf(*d, "chain.s[2].gain.y"), 8.0);
}

TEST(BlockReferencesTest, NamesWithEmptyPartsAreRefused) {
  for (const std::string name : {"", "d.", ".d", "d..c"}) {
    DiagramBuilder b;
    try {
      b.AddBlock(MakeBlock("constant", name, {{"value", "1"}}), "code.cc:1");
      ADD_FAILURE() << "accepted '" << name << "'";
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), StartsWith("code.cc:1: block name '" + name + "' "));
      EXPECT_THAT(e.what(), HasSubstr("an instance path such as d[1].fr")) << name;
    }
  }
}

// The block is the longest prefix that names one: the rest is a port whose
// name may hold dots.
TEST(BlockReferencesTest, PortsWithDotsBelongToTheLongestBlockName) {
  DiagramBuilder b;
  b.AddBlock(std::make_unique<Sensors>("m"));
  b.AddBlock(MakeBlock("gain", "g", {{"k", "10"}}));
  b.Connect("m.s[1].x", "g.u");
  const auto d = b.Build();
  const SignalRef s1 = d->ResolveSignal("m.s[1].x");
  EXPECT_EQ(s1.name, "m.s[1].x");
  EXPECT_EQ(s1.offset, d->layout(d->FindBlock("m")).output_offset[1]);
  EXPECT_EQ(ValueOf(*d, "g.y"), 20.0);
  EXPECT_EQ(ValueOf(*d, "m.s[0].x"), 1.0);

  // with a block named "m.s[1]" too, "m.s[1].x" is its port x
  DiagramBuilder both;
  both.AddBlock(std::make_unique<Sensors>("m"));
  both.AddBlock(MakeBlock("constant", "m.s[1]", {{"value", "7"}}));
  const auto with_inner = both.Build();
  EXPECT_EQ(with_inner->ResolveSignal("m.s[1].y").offset,
            with_inner->layout(with_inner->FindBlock("m.s[1]")).output_offset[0]);
  EXPECT_THAT(ResolveError(*with_inner, "m.s[1].x"), HasSubstr("block 'm.s[1]' has no output 'x'"));
}

// Messages for names that resolve to no block are what they were before
// names held dots: the part before the last dot is the block asked for.
TEST(BlockReferencesTest, UnknownBlocksAreNamedAsWritten) {
  DiagramBuilder b;
  b.AddBlock(std::make_unique<Sensors>("sensor"));
  const auto d = b.Build();
  EXPECT_THAT(ResolveError(*d, "sensr.s[0].x"), HasSubstr("signal 'sensr.s[0].x': no block named 'sensr.s[0]'"));
  EXPECT_THAT(ResolveError(*d, "sensr.y"), HasSubstr("no block named 'sensr' (did you mean 'sensor'?)"));
  EXPECT_THAT(ResolveError(*d, "sensor.s[2].x"), HasSubstr("block 'sensor' has no output 's[2].x'"));

  DiagramBuilder c;
  c.AddBlock(MakeBlock("gain", "g", {{"k", "1"}}));
  c.Connect("gg.y", "g.u", "d.xml:3");
  EXPECT_THAT(BuildError(&c), HasSubstr("d.xml:3: connection from 'gg.y' to 'g.u': there is no block named 'gg' "
                                        "(did you mean 'g'?)"));
}

TEST(BlockReferencesTest, AliasesNameTheirTargetsOutput) {
  DiagramBuilder b;
  b.AddBlock(MakeBlock("constant", "d[1].fr", {{"value", "5"}}));
  b.AddBlock(MakeBlock("gain", "g", {{"k", "3"}}));
  b.AddSignalAlias("top.F", "d[1].F");  // an alias of an alias, added before it
  b.AddSignalAlias("d[1].F", "d[1].fr.y");
  b.Connect("top.F", "g.u");  // a connection from an alias
  const auto d = b.Build();
  const SignalRef alias = d->ResolveSignal("d[1].F"), target = d->ResolveSignal("d[1].fr.y");
  EXPECT_EQ(alias.name, "d[1].F");
  EXPECT_EQ(alias.offset, target.offset);
  EXPECT_EQ(alias.width, target.width);
  EXPECT_EQ(d->ResolveSignal("top.F").name, "top.F");
  EXPECT_EQ(d->ResolveSignal("top.F").offset, target.offset);
  EXPECT_EQ(ValueOf(*d, "g.y"), 15.0);
}

TEST(BlockReferencesTest, FaultyAliasesAreRefusedWithTheirOrigin) {
  const auto error = [](const std::string& alias, const std::string& target) {
    DiagramBuilder b;
    b.AddBlock(MakeBlock("constant", "d[1].fr", {{"value", "5"}}));
    b.AddSignalAlias(alias, target, "sub.xml:4");
    b.AddSignalAlias("loop.a", "loop.b", "sub.xml:5");
    b.AddSignalAlias("loop.b", "loop.a", "sub.xml:6");
    return BuildError(&b);
  };
  EXPECT_THAT(error("d[1].F", "d[1].fr.z"),
              HasSubstr("sub.xml:4: signal alias 'd[1].F' for 'd[1].fr.z': signal 'd[1].fr.z': block 'd[1].fr' has "
                        "no output 'z'"));
  EXPECT_THAT(error("d[1].F", "d[2].fr.y"),
              HasSubstr("sub.xml:4: signal alias 'd[1].F' for 'd[2].fr.y': signal 'd[2].fr.y': no block named "
                        "'d[2].fr'"));
  EXPECT_THAT(error("d[1].fr.y", "d[1].fr"), HasSubstr("sub.xml:4: signal alias 'd[1].fr.y' for 'd[1].fr': "
                                                       "'d[1].fr.y' already names an output of block 'd[1].fr'"));
  EXPECT_THAT(error("d[1].F", "d[1].fr.y"), HasSubstr("sub.xml:5: signal alias 'loop.a' for 'loop.b': the aliases "
                                                      "go round in a circle"));

  DiagramBuilder twice;
  twice.AddSignalAlias("a.F", "x.y", "sub.xml:4");
  try {
    twice.AddSignalAlias("a.F", "z.y", "sub.xml:9");
    ADD_FAILURE() << "accepted twice";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("sub.xml:9: signal alias 'a.F' is given twice (first at sub.xml:4)"));
  }

  // an alias is an output: a connection cannot feed it
  DiagramBuilder to_alias;
  to_alias.AddBlock(MakeBlock("constant", "c", {{"value", "1"}}));
  to_alias.AddSignalAlias("a.F", "c.y");
  to_alias.Connect("c.y", "a.F", "d.xml:7");
  EXPECT_THAT(BuildError(&to_alias), HasSubstr("d.xml:7: connection from 'c.y' to 'a.F': 'a.F' is another name for "
                                               "the output c.y, not an input"));
}

}  // namespace
}  // namespace mechflow::blocks::testing
