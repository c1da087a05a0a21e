// What `mechflow check` and `mechflow graph` show of a flattened diagram's
// subsystem and part instances: an indented tree, and nested DOT clusters
// holding the blocks of each subsystem instance. The diagram is made here by
// hand, as flattening would make it (block names that are instance paths).

#include "cli/instance_tree.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli/report.h"
#include "tests/blocks/block_test_util.h"
#include "tests/cli/mechflow_command.h"

namespace mechflow::cli {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

diagrams::InstanceDesc Instance(const std::string& path, const std::string& kind, const std::string& file, int line) {
  return {path, kind, file, {"top.xml", line}};
}

TEST(InstanceTreeTest, ParentsAreTheLongestEnclosingInstances) {
  const InstanceTree tree({"chain", "chain.s[0]", "chain.s[1]", "chain.s[1].d", "m.arm[0]", "chainx"});
  EXPECT_THAT(tree.roots(), ElementsAre(0, 4, 5));
  EXPECT_THAT(tree.children(0), ElementsAre(1, 2));
  EXPECT_THAT(tree.children(2), ElementsAre(3));
  EXPECT_EQ(tree.Enclosing("chain.s[1].d.g"), 3);
  EXPECT_EQ(tree.Enclosing("chain.s[1].g"), 2);
  EXPECT_EQ(tree.Enclosing("chainx"), -1);  // not in itself
  EXPECT_EQ(tree.Enclosing("chain"), -1);
  EXPECT_EQ(tree.Enclosing("gain"), -1);
}

TEST(InstanceTreeTest, CheckListsTheInstancesIndentedByDepth) {
  std::ostringstream none;
  PrintInstanceTree({}, none);
  EXPECT_EQ(none.str(), "");
  std::ostringstream out;
  PrintInstanceTree({Instance("chain", "subsystem", "chain.xml", 5), Instance("chain.s[0]", "subsystem", "stage.xml", 0),
                     Instance("m.arm[0]", "part", "arm.xml", 9)},
                    out);
  EXPECT_EQ(out.str(),
            "\ninstances:\n"
            "  chain  subsystem chain.xml  (included at top.xml:5)\n"
            "    chain.s[0]  subsystem stage.xml  (included at top.xml:0)\n"
            "  m.arm[0]  part arm.xml  (included at top.xml:9)\n");
}

// d[0] and d[1], the second holding e; "dx" is no instance's block.
diagrams::LoadedDiagram Flattened() {
  using blocks::testing::MakeBlock;
  blocks::DiagramBuilder builder;
  builder.AddBlock(MakeBlock("constant", "src", {{"value", "1"}}));
  builder.AddBlock(MakeBlock("gain", "d[0].g", {{"k", "2"}}));
  builder.AddBlock(MakeBlock("gain", "d[1].g", {{"k", "2"}}));
  builder.AddBlock(MakeBlock("gain", "d[1].e.g", {{"k", "2"}}));
  builder.AddBlock(MakeBlock("gain", "dx", {{"k", "2"}}));
  builder.Connect("src", "d[0].g.u");
  builder.Connect("d[0].g", "d[1].g.u");
  builder.Connect("d[1].g", "d[1].e.g.u");
  builder.Connect("d[1].e.g", "dx.u");
  diagrams::LoadedDiagram loaded;
  loaded.diagram = builder.Build();
  loaded.identifiers = std::make_unique<scripting::IdentifierTable>();
  loaded.description.name = "top";
  loaded.description.instances = {Instance("d[0]", "subsystem", "d.xml", 3), Instance("d[1]", "subsystem", "d.xml", 3),
                                  Instance("d[1].e", "subsystem", "e.xml", 4), Instance("m.arm[0]", "part", "arm.xml", 6)};
  return loaded;
}

TEST(InstanceTreeTest, GraphDrawsEachSubsystemInstanceAsANestedCluster) {
  const diagrams::LoadedDiagram loaded = Flattened();
  std::ostringstream dot;
  PrintDot(loaded, dot);
  const std::string text = dot.str();
  // blocks outside every instance first, then the clusters, nested
  const auto at = [&](const std::string& what) {
    const auto found = text.find(what);
    EXPECT_NE(found, std::string::npos) << what << " in\n" << text;
    return found;
  };
  const auto src = at("  b0 [label="), dx = at("  b4 [label="), d0 = at("  subgraph cluster_0 {\n    label=\"d[0]\";\n"),
             g0 = at("    b1 [label="), d1 = at("  subgraph cluster_1 {\n    label=\"d[1]\";\n"),
             g1 = at("    b2 [label="), e = at("    subgraph cluster_2 {\n      label=\"d[1].e\";\n"),
             eg = at("      b3 [label=");
  EXPECT_LT(src, dx);
  EXPECT_LT(dx, d0);
  EXPECT_LT(d0, g0);
  EXPECT_LT(g0, d1);
  EXPECT_LT(d1, g1);
  EXPECT_LT(g1, e);
  EXPECT_LT(e, eg);
  EXPECT_THAT(text, HasSubstr("      b3 [label=\"{{<i0> u}|d[1].e.g\\n(gain)|{<o0> y}}\"];\n    }\n  }\n"));
  EXPECT_THAT(text, ::testing::Not(HasSubstr("arm")));  // a part holds no blocks
  if (std::system("command -v dot >/dev/null 2>&1") == 0) {
    const std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "instance_clusters.dot";
    std::ofstream(file) << text;
    EXPECT_EQ(std::system(("dot -Tsvg " + file.string() + " >/dev/null").c_str()), 0);
  }
}

TEST(InstanceTreeTest, CheckEndsWithTheInstances) {
  const diagrams::LoadedDiagram loaded = Flattened();
  std::ostringstream out;
  PrintCheck(loaded, out);
  EXPECT_THAT(out.str(), ::testing::EndsWith("logged columns: 0\n\ninstances:\n"
                                             "  d[0]  subsystem d.xml  (included at top.xml:3)\n"
                                             "  d[1]  subsystem d.xml  (included at top.xml:3)\n"
                                             "    d[1].e  subsystem e.xml  (included at top.xml:4)\n"
                                             "  m.arm[0]  part arm.xml  (included at top.xml:6)\n"));
}

// The same from a diagram file: an array of subsystems inside a subsystem,
// found through --library.
TEST(InstanceTreeTest, CheckAndGraphShowTheInstancesOfASubsystemDiagram) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "instance_tree_cli";
  fs::create_directories(dir / "d");
  fs::create_directories(dir / "lib");
  std::ofstream(dir / "lib" / "stage.xml") << R"(<subsystem name="stage">
  <input name="u"/><output name="y"/>
  <blocks><block type="gain" name="g" k="2"/></blocks>
  <connections><connect from="u" to="g.u"/><connect from="g.y" to="y"/></connections>
</subsystem>
)";
  std::ofstream(dir / "lib" / "chain.xml") << R"(<subsystem name="chain">
  <input name="u"/><output name="y"/>
  <blocks><block type="subsystem" name="s" src="stage.xml" count="2"/></blocks>
  <connections><connect from="u" to="s[0].u"/><connect from="s[0].y" to="s[1].u"/><connect from="s[1].y" to="y"/>
  </connections>
</subsystem>
)";
  const std::string diagram = (dir / "d" / "top.xml").string();
  std::ofstream(diagram) << R"(<diagram name="top">
  <blocks>
    <block type="constant" name="c" value="1"/>
    <block type="subsystem" name="chain" src="chain.xml"/>
    <block type="gain" name="out" k="1"/>
  </blocks>
  <connections><connect from="c.y" to="chain.u"/><connect from="chain.y" to="out.u"/></connections>
</diagram>
)";
  const std::string library = " --library " + (dir / "lib").string();
  const auto check = testing::RunMechflow("check " + diagram + library);
  ASSERT_EQ(check.exit_code, 0) << check.err;
  const std::string lib = (dir / "lib").string() + "/";
  EXPECT_THAT(check.out, HasSubstr("\ninstances:\n"
                                   "  chain  subsystem " + lib + "chain.xml  (included at " + diagram + ":4)\n"
                                   "    chain.s[0]  subsystem " + lib + "stage.xml  (included at " + lib + "chain.xml:3)\n"
                                   "    chain.s[1]  subsystem " + lib + "stage.xml  (included at " + lib + "chain.xml:3)\n"
                                   "\n" + diagram + ": ok\n"));
  const auto graph = testing::RunMechflow("graph " + diagram + library);
  ASSERT_EQ(graph.exit_code, 0) << graph.err;
  EXPECT_THAT(graph.out, HasSubstr("  subgraph cluster_0 {\n    label=\"chain\";\n"
                                   "    subgraph cluster_1 {\n      label=\"chain.s[0]\";\n"
                                   "      b1 [label=\"{{<i0> u}|chain.s[0].g\\n(gain)|{<o0> y}}\"];\n    }\n"
                                   "    subgraph cluster_2 {\n      label=\"chain.s[1]\";\n"
                                   "      b2 [label=\"{{<i0> u}|chain.s[1].g\\n(gain)|{<o0> y}}\"];\n    }\n  }\n"));
}

}  // namespace
}  // namespace mechflow::cli
