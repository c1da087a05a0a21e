// Subsystem and part instances (diagrams/instances.h): the rules of
// flattening and every refusal, each through diagrams::LoadDiagram on files
// written to a folder of the test (the CLI where the exit code matters).

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"
#include "tests/test_util.h"

namespace mechflow::diagrams {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using testing::InputErrorOf;

// Load options with --set NAME=VALUE, and with --variant NAME.
LoadOptions Setting(std::vector<std::pair<std::string, double>> overrides) {
  LoadOptions options;
  options.overrides = std::move(overrides);
  return options;
}
LoadOptions Variant(const std::string& name) {
  LoadOptions options;
  options.variants = {name};
  return options;
}

class InstancesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("instances_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  void Write(const std::string& name, const std::string& text) {
    fs::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name) << text;
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  // Diagram `main.xml` with these identifiers, blocks and connections (the
  // identifiers start on line 3, one a line).
  void WriteMain(const std::string& identifiers, const std::string& blocks, const std::string& connections = "",
                 const std::string& more = "") {
    Write("main.xml", "<diagram name='main'>\n<identifiers>\n" + identifiers + "</identifiers>\n<blocks>\n" + blocks +
                          "</blocks>\n<connections>\n" + connections + "</connections>\n" + more +
                          "<solver t_end='1'/>\n</diagram>\n");
  }

  LoadedDiagram Load(const LoadOptions& options = {}) { return LoadDiagram(Path("main.xml"), options); }
  std::string ErrorOf(const LoadOptions& options = {}) {
    return InputErrorOf([&] { Load(options); });
  }
  // The message, with the test's folder taken out of file names.
  std::string Relative(std::string message) const {
    const std::string folder = dir_.string() + "/";
    for (std::size_t at; (at = message.find(folder)) != std::string::npos;) message.erase(at, folder.size());
    return message;
  }
  std::string Error(const LoadOptions& options = {}) { return Relative(ErrorOf(options)); }

  static double Value(const LoadedDiagram& d, const std::string& name) { return d.identifiers->Value(name); }

  // Runs main.xml; the last value of the logged column `label`.
  double Final(const std::string& label, const LoadOptions& options = {}) {
    const testing::XmlRun run = testing::RunDescription(ReadDiagramFile(Path("main.xml"), {}, options.library), options);
    return run.Column(label).back();
  }

  fs::path dir_;
};

// y = k^2 u, k a parameter (default 2), k2 a local identifier.
const char* kScale =
    "<subsystem name='scale'>\n"                                            // 1
    "  <parameter name='k' default='2'/>\n"                                 // 2
    "  <input name='u'/>\n"                                                 // 3
    "  <output name='y'/>\n"                                                // 4
    "  <identifiers><identifier name='k2' value='k*k'/></identifiers>\n"    // 5
    "  <blocks><block type='gain' name='g' k='k2'/></blocks>\n"             // 6
    "  <connections>\n"                                                     // 7
    "    <connect from='u' to='g.u'/>\n"                                    // 8
    "    <connect from='g.y' to='y'/>\n"                                    // 9
    "  </connections>\n"                                                    // 10
    "</subsystem>\n";

// --- parameters ----------------------------------------------------------------

TEST_F(InstancesTest, ParameterWithoutDefaultNorParamNamesBothLines) {
  Write("p.xml", "<subsystem name='p'>\n<parameter name='mass'/>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='d' src='p.xml'/>\n");
  EXPECT_EQ(Error(), "main.xml:5: d gives no <param name=\"mass\"> and subsystem 'p' (p.xml) as d has no default for "
                     "it (p.xml:2)");
}

TEST_F(InstancesTest, ParamTheSubsystemDoesNotDeclareSuggestsOne) {
  Write("scale.xml", kScale);
  WriteMain("", "<block type='subsystem' name='d' src='scale.xml'>\n<param name='kk' value='3'/>\n</block>\n");
  EXPECT_EQ(Error(), "main.xml:6: subsystem 'scale' (scale.xml) as d has no parameter 'kk' (did you mean 'k'?); its "
                     "parameters: k (scale.xml:1)");
}

TEST_F(InstancesTest, ParamGivenTwiceRefused) {
  Write("scale.xml", kScale);
  WriteMain("", "<block type='subsystem' name='d' src='scale.xml'>\n<param name='k' value='3'/>\n"
                "<param name='k' value='4'/>\n</block>\n");
  EXPECT_EQ(Error(), "main.xml:7: parameter 'k' of d is given twice");
}

TEST_F(InstancesTest, ParamOnAnOrdinaryBlockRefused) {
  WriteMain("", "<block type='gain' name='g' k='1'>\n<param name='k' value='3'/>\n</block>\n");
  EXPECT_THAT(Error(), StartsWith("main.xml:6: <param> gives a subsystem's parameter; block 'g' is a gain"));
}

TEST_F(InstancesTest, ParameterNamedIndexRefused) {
  Write("p.xml", "<subsystem name='p'>\n<parameter name='index' default='1'/>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='d' src='p.xml'/>\n");
  EXPECT_THAT(Error(), StartsWith("p.xml:2: parameter name 'index' is kept for arrays"));
}

TEST_F(InstancesTest, ParametersAndLocalIdentifiersGetPaths) {
  Write("scale.xml", kScale);
  WriteMain("<identifier name='k0' value='1.5'/>\n",
            "<block type='subsystem' name='d' src='scale.xml'>\n<param name='k' value='2*k0'/>\n</block>\n"
            "<block type='subsystem' name='e' src='scale.xml'/>\n<block type='constant' name='one' value='1'/>\n",
            "<connect from='one.y' to='d.u'/>\n<connect from='one.y' to='e.u'/>\n");
  const LoadedDiagram d = Load();
  EXPECT_EQ(Value(d, "d.k"), 3);
  EXPECT_EQ(Value(d, "d.k2"), 9);
  EXPECT_EQ(Value(d, "e.k"), 2);
  EXPECT_EQ(Value(d, "e.k2"), 4);
}

TEST_F(InstancesTest, NameDeclaredFurtherDownRefusedAsSuch) {
  Write("p.xml", "<subsystem name='p'>\n<parameter name='a' default='2*b'/>\n<parameter name='b' default='1'/>\n"
                 "</subsystem>\n");
  WriteMain("<identifier name='b' value='5'/>\n", "<block type='subsystem' name='d' src='p.xml'/>\n");
  EXPECT_EQ(Error(), "p.xml:2: in d (main.xml:6): parameter 'a' default: 'b' is declared below it (p.xml:3); "
                     "parameters and identifiers may use those declared above them: move it up");
  Write("p.xml", "<subsystem name='p'>\n<identifiers>\n<identifier name='a' value='2*b'/>\n"
                 "<identifier name='b' value='1'/>\n</identifiers>\n</subsystem>\n");
  EXPECT_THAT(Error(), StartsWith("p.xml:3: in d (main.xml:6): identifier 'a': 'b' is declared below it (p.xml:4)"));
}

// --- closed scope ----------------------------------------------------------------

TEST_F(InstancesTest, LocalIdentifierDoesNotLeakOut) {
  Write("scale.xml", kScale);
  WriteMain("<identifier name='outside' value='k2+1'/>\n", "<block type='subsystem' name='d' src='scale.xml'/>\n");
  EXPECT_THAT(Error(), AllOf(StartsWith("main.xml:3"), HasSubstr("k2")));
}

TEST_F(InstancesTest, ParentIdentifierDoesNotLeakIn) {
  Write("p.xml", "<subsystem name='p'>\n<identifiers>\n<identifier name='c' value='2*c_base'/>\n</identifiers>\n"
                 "</subsystem>\n");
  WriteMain("<identifier name='c_base' value='1'/>\n", "<block type='subsystem' name='d' src='p.xml'/>\n");
  EXPECT_THAT(Error(), StartsWith("p.xml:3: in d (main.xml:6): identifier 'c': 'c_base' is not visible inside "
                                  "subsystem 'p' (p.xml) as d: only its parameters and identifiers are; declare "
                                  "<parameter name=\"c_base\"/>"));
}

TEST_F(InstancesTest, ParameterShadowsTheParentIdentifierOfItsName) {
  Write("p.xml", "<subsystem name='p'>\n<parameter name='c' default='5'/>\n<identifiers>\n"
                 "<identifier name='twice' value='2*c'/>\n</identifiers>\n</subsystem>\n");
  WriteMain("<identifier name='c' value='1'/>\n", "<block type='subsystem' name='d' src='p.xml'/>\n");
  const LoadedDiagram d = Load();
  EXPECT_EQ(Value(d, "d.twice"), 10);
  EXPECT_EQ(Value(d, "c"), 1);
}

// Names Lua code binds (local, function parameters, for) are its own: a diagram identifier of that name is
// no leak, a parameter of that name is refused (the code would read neither as meant).
TEST_F(InstancesTest, NamesLuaCodeBindsAreItsOwn) {
  Write("p.xml", "<subsystem name='p'>\n<parameter name='k' default='3'/>\n<output name='y'/>\n<blocks>\n"
                 "<block type='lua' name='f'>\nfunction outputs(t)\n  local g = 2\n  for i = 1, 2 do g = g + i end\n"
                 "  return k * g\nend\n</block>\n</blocks>\n<connections><connect from='f.y' to='y'/></connections>\n"
                 "</subsystem>\n");
  WriteMain("<identifier name='g' value='100'/>\n<identifier name='i' value='100'/>\n",
            "<block type='subsystem' name='d' src='p.xml'/>\n<block type='gain' name='h' k='1'/>\n",
            "<connect from='d.y' to='h.u'/>\n", "<output>\n<log signal='h.y' label='y'/>\n</output>\n");
  EXPECT_NEAR(Final("y"), 15, 1e-12);
  std::string text = testing::ReadFile(dir_ / "p.xml");
  text.replace(text.find("local g = 2"), 11, "local k = 2");
  Write("p.xml", text);
  EXPECT_THAT(Error(), HasSubstr("the code binds 'k' (local, function parameter or for variable), which is also a "
                                 "parameter or identifier of subsystem 'p' (p.xml) as d; rename one of them"));
}

// --- reading files ---------------------------------------------------------------

TEST_F(InstancesTest, SrcIsRelativeToTheIncludingFile) {
  Write("parts/outer.xml", "<subsystem name='outer'>\n<blocks>\n<block type='subsystem' name='i' src='inner.xml'/>\n"
                           "</blocks>\n</subsystem>\n");
  Write("parts/inner.xml", "<subsystem name='inner'>\n<parameter name='z' default='7'/>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='o' src='parts/outer.xml'/>\n");
  EXPECT_EQ(Value(Load(), "o.i.z"), 7);
}

TEST_F(InstancesTest, LibraryFolderWhenNotBeside) {
  Write("lib/inner.xml", "<subsystem name='inner'>\n<parameter name='z' default='7'/>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='o' src='inner.xml'/>\n");
  EXPECT_THAT(Error(), StartsWith("main.xml:5: subsystem: file 'inner.xml' not found"));
  LoadOptions options;
  options.library = {Path("lib")};
  EXPECT_EQ(Value(Load(options), "o.z"), 7);
}

// The CLI: exit 2 and file:line for each file problem.
TEST_F(InstancesTest, FileProblemsExitTwoWithFileAndLine) {
  struct Case {
    std::string files_main_src, expected;
  };
  Write("self.xml", "<subsystem name='s'>\n<blocks>\n<block type='subsystem' name='again' src='self.xml'/>\n"
                    "</blocks>\n</subsystem>\n");
  Write("a.xml", "<subsystem name='a'>\n<blocks>\n<block type='subsystem' name='b' src='b.xml'/>\n"
                 "</blocks>\n</subsystem>\n");
  Write("b.xml", "<subsystem name='b'>\n<blocks>\n<block type='subsystem' name='a' src='a.xml'/>\n"
                 "</blocks>\n</subsystem>\n");
  fs::create_directories(dir_ / "folder.xml");
  for (int k = 0; k <= 33; ++k)
    Write("deep" + std::to_string(k) + ".xml",
          "<subsystem name='deep'>\n<blocks>\n<block type='subsystem' name='n' src='deep" + std::to_string(k + 1) +
              ".xml'/>\n</blocks>\n</subsystem>\n");
  Write("deep34.xml", "<subsystem name='deep'/>\n");
  const std::pair<std::string, std::string> cases[] = {
      {"self.xml", "self.xml:3: <block> 'again' includes"},
      {"a.xml", "b.xml:3: <block> 'a' includes"},
      {"folder.xml", "main.xml:5: subsystem: file 'folder.xml' is not a regular file"},
      {"missing.xml", "main.xml:5: subsystem: file 'missing.xml' not found"},
      {"deep0.xml", ".xml:3: <block> 'n': subsystems and parts nest more than 32 levels deep"},
  };
  for (const auto& [src, expected] : cases) {
    SCOPED_TRACE(src);
    WriteMain("", "<block type='subsystem' name='d' src='" + src + "'/>\n");
    const auto run = testing::RunMechflow("run " + Path("main.xml") + " --out " + Path("out"));
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_THAT(Relative(run.err), HasSubstr(expected));
  }
}

// --- arrays ------------------------------------------------------------------------

TEST_F(InstancesTest, ArrayCountFromAnIdentifierAndItsOverride) {
  Write("p.xml", "<subsystem name='p'>\n<parameter name='w' default='10*index+count'/>\n</subsystem>\n");
  WriteMain("<identifier name='n' value='2'/>\n", "<block type='subsystem' name='d' src='p.xml' count='n'/>\n");
  const LoadedDiagram two = Load();
  EXPECT_EQ(Value(two, "d[1].w"), 12);
  EXPECT_FALSE(two.identifiers->Has("d[2].w"));
  const LoadedDiagram three = Load(Setting({{"n", 3}}));
  EXPECT_EQ(Value(three, "d[2].w"), 23);
  LoadOptions expression;  // --set n=1+2: the count follows it too
  expression.expression_overrides = {{"n", "1+2"}};
  const LoadedDiagram also_three = Load(expression);
  EXPECT_EQ(Value(also_three, "d[2].w"), 23);
}

TEST_F(InstancesTest, SetWithAStarSetsEveryElement) {
  Write("p.xml", "<subsystem name='p'>\n<parameter name='w' default='1'/>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='d' src='p.xml' count='3'/>\n");
  const LoadedDiagram d = Load(Setting({{"d[*].W", 5}, {"d[1].w", 7}}));  // in order: the later one wins
  EXPECT_EQ(Value(d, "d[0].w"), 5);
  EXPECT_EQ(Value(d, "d[1].w"), 7);
  EXPECT_EQ(Value(d, "d[2].w"), 5);
  EXPECT_THAT(ErrorOf(Setting({{"e[*].w", 5}})), StartsWith("--set e[*].w: no identifier matches 'e[*].w'"));
}

TEST_F(InstancesTest, ParamSeesTheNewElementsIndex) {
  Write("p.xml", "<subsystem name='p'>\n<parameter name='w'/>\n</subsystem>\n");
  WriteMain("<identifier name='w0' value='100'/>\n",
            "<block type='subsystem' name='d' src='p.xml' count='3'>\n<param name='w' value='w0*(1+index)/count'/>\n"
            "</block>\n");
  const LoadedDiagram d = Load();
  EXPECT_NEAR(Value(d, "d[2].w"), 100, 1e-12);
  EXPECT_NEAR(Value(d, "d[0].w"), 100.0 / 3, 1e-12);
}

TEST_F(InstancesTest, BadCountsRefused) {
  Write("p.xml", "<subsystem name='p'/>\n");
  for (const std::string count : {"0", "1.5", "1e9", "-1", "0/0"}) {
    SCOPED_TRACE(count);
    WriteMain("", "<block type='subsystem' name='d' src='p.xml' count='" + count + "'/>\n");
    EXPECT_THAT(Error(), StartsWith("main.xml:5: count"));
    EXPECT_THAT(Error(), HasSubstr(count));
  }
}


// --- overrides -----------------------------------------------------------------------

TEST_F(InstancesTest, SetAndVariantReachAnArrayElementsParameter) {
  Write("scale.xml", kScale);
  WriteMain("", "<block type='subsystem' name='d' src='scale.xml' count='2'/>\n"
                "<block type='constant' name='one' value='1'/>\n",
            "<connect from='one.y' to='d[0].u'/>\n<connect from='one.y' to='d[1].u'/>\n",
            "<variants name='g'>\n<variant name='stiff'>\n<set identifier='d[1].k' value='5'/>\n</variant>\n"
            "</variants>\n");
  const LoadedDiagram set = Load(Setting({{"d[1].k", 3}}));
  EXPECT_EQ(Value(set, "d[1].k2"), 9);
  EXPECT_EQ(Value(set, "d[0].k2"), 4);
  EXPECT_EQ(Value(Load(Variant("stiff")), "d[1].k2"), 25);
  EXPECT_THAT(ErrorOf(Setting({{"d[1].k2", 3}})), HasSubstr("d[1].k2"));
  EXPECT_THAT(ErrorOf(Setting({{"d[2].k", 3}})), HasSubstr("d[2].k"));
}

TEST_F(InstancesTest, SetOfAParameterGivenByAnExpressionRefused) {
  Write("scale.xml", kScale);
  WriteMain("<identifier name='k0' value='1'/>\n",
            "<block type='subsystem' name='d' src='scale.xml'>\n<param name='k' value='2*k0'/>\n</block>\n"
            "<block type='constant' name='one' value='1'/>\n",
            "<connect from='one.y' to='d.u'/>\n");
  EXPECT_THAT(ErrorOf(Setting({{"d.k", 3}})), StartsWith("--set d.k: "));
  EXPECT_EQ(Value(Load(Setting({{"k0", 3}})), "d.k2"), 36);
}

// --- ports and nesting -----------------------------------------------------------------

// x' = k^2 * 1 through two levels of subsystems: x(1) = k^2.
TEST_F(InstancesTest, PortsPassThroughTwoLevels) {
  Write("scale.xml", kScale);
  Write("outer.xml",
        "<subsystem name='outer'>\n<parameter name='k'/>\n<input name='a'/>\n<output name='b'/>\n<output name='same'/>\n"
        "<blocks>\n<block type='subsystem' name='s' src='scale.xml'>\n<param name='k' value='k'/>\n</block>\n</blocks>\n"
        "<connections>\n<connect from='a' to='s.u'/>\n<connect from='s.y' to='b'/>\n<connect from='a' to='same'/>\n"
        "</connections>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='o' src='outer.xml'>\n<param name='k' value='3'/>\n</block>\n"
                "<block type='constant' name='one' value='1'/>\n<block type='integrator' name='x' initial='0'/>\n"
                "<block type='integrator' name='z' initial='0'/>\n",
            "<connect from='one.y' to='o.a'/>\n<connect from='o.b' to='x.u'/>\n<connect from='o.same' to='z.u'/>\n",
            "<output>\n<log signal='x.y' label='x'/>\n<log signal='z.y' label='z'/>\n</output>\n");
  EXPECT_NEAR(Final("x"), 9, 1e-6);
  EXPECT_NEAR(Final("z"), 1, 1e-6);
}

TEST_F(InstancesTest, AFedInputNothingInsideReadsRefused) {
  Write("p.xml", "<subsystem name='p'>\n<input name='u'/>\n<input name='unused'/>\n<output name='y'/>\n"
                 "<blocks><block type='gain' name='g' k='2'/></blocks>\n"
                 "<connections><connect from='u' to='g.u'/><connect from='g.y' to='y'/></connections>\n"
                 "</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='d' src='p.xml'/>\n<block type='clock' name='c'/>\n",
            "<connect from='c.y' to='d.u'/>\n");
  EXPECT_EQ(Error(), "");  // an input left open is no mistake
  WriteMain("", "<block type='subsystem' name='d' src='p.xml'/>\n<block type='clock' name='c'/>\n",
            "<connect from='c.y' to='d.u'/>\n<connect from='c.y' to='d.unused'/>\n");
  EXPECT_THAT(Error(), StartsWith("main.xml:10: connection to 'd.unused': nothing inside d reads its input 'unused' "
                                  "(p.xml:3"));
}

TEST_F(InstancesTest, PortOfAnArrayWithoutIndexRefused) {
  Write("scale.xml", kScale);
  WriteMain("", "<block type='subsystem' name='d' src='scale.xml' count='3'/>\n<block type='clock' name='c'/>\n",
            "<connect from='c.y' to='d.u'/>\n");
  EXPECT_EQ(Error(), "main.xml:9: 'd.u': d is an array of 3 (count=); name one element, d[0].u to d[2].u");
  WriteMain("", "<block type='subsystem' name='d' src='scale.xml' count='3'/>\n<block type='clock' name='c'/>\n",
            "<connect from='c.y' to='d[*].u'/>\n", "<output>\n<log signal='d.y'/>\n</output>\n");
  EXPECT_EQ(Error(), "main.xml:12: 'd.y': d is an array of 3 (count=); name one element, d[0].y to d[2].y");
}

TEST_F(InstancesTest, UnfedInputUsedInsideRefused) {
  Write("scale.xml", kScale);
  WriteMain("", "<block type='subsystem' name='d' src='scale.xml'/>\n");
  EXPECT_EQ(Error(), "scale.xml:8: in d (main.xml:5): 'd.u' is an input of d that nothing feeds; connect it where d "
                     "is used");
}

TEST_F(InstancesTest, OutputNothingFeedsRefused) {
  Write("p.xml", "<subsystem name='p'>\n<output name='y'/>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='d' src='p.xml'/>\n<block type='integrator' name='x' initial='0'/>\n",
            "<connect from='d.y' to='x.u'/>\n");
  const std::string read = Error();
  EXPECT_EQ(read, "p.xml:2: in d (main.xml:5): output 'y' of subsystem 'p' (p.xml) as d: nothing inside feeds it; "
                  "connect a block's output to it (<connect from=\"BLOCK.PORT\" to=\"y\"/>) or remove it");
  WriteMain("", "<block type='subsystem' name='d' src='p.xml'/>\n");
  EXPECT_EQ(Error(), read);
}

TEST_F(InstancesTest, PortFedTwiceRefused) {
  Write("scale.xml", kScale);
  WriteMain("", "<block type='subsystem' name='d' src='scale.xml'/>\n<block type='constant' name='one' value='1'/>\n",
            "<connect from='one.y' to='d.u'/>\n<connect from='one.y' to='d.u'/>\n");
  EXPECT_THAT(Error(), StartsWith("main.xml:10: port 'd.u' is fed twice (first at main.xml:9)"));
}

TEST_F(InstancesTest, PortNamedLikeABlockRefused) {
  Write("p.xml", "<subsystem name='p'>\n<input name='g'/>\n<blocks><block type='gain' name='g' k='1'/></blocks>\n"
                 "</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='d' src='p.xml'/>\n");
  EXPECT_THAT(Error(), StartsWith("p.xml:3: in d (main.xml:5): block 'g' has the name of a port of subsystem 'p'"));
}

TEST_F(InstancesTest, PortsJoinedInALoopRefused) {
  Write("p.xml", "<subsystem name='p'>\n<input name='u'/>\n<output name='y'/>\n"
                 "<connections><connect from='u' to='y'/></connections>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='d' src='p.xml'/>\n<block type='integrator' name='x' initial='0'/>\n",
            "<connect from='d.y' to='d.u'/>\n<connect from='d.y' to='x.u'/>\n");
  EXPECT_THAT(Error(), HasSubstr("loop"));
}

TEST_F(InstancesTest, NamesTakenTwiceRefused) {
  Write("p.xml", "<subsystem name='p'/>\n");
  WriteMain("", "<block type='subsystem' name='d' src='p.xml'/>\n<block type='gain' name='d' k='1'/>\n");
  EXPECT_THAT(Error(), StartsWith("main.xml:6: block name 'd' is used twice (first at main.xml:5)"));
  WriteMain("", "<block type='subsystem' name='d' src='p.xml'/>\n<block type='subsystem' name='d' src='p.xml'/>\n");
  EXPECT_THAT(Error(), StartsWith("main.xml:6: subsystem name 'd' is used twice (first at main.xml:5)"));
}

// A non-array subsystem inside an array element: its <param> is written in
// the element's file, where `index` is the element's.
TEST_F(InstancesTest, IndexOfTheIncludingElementInANestedParam) {
  Write("inner.xml", "<subsystem name='inner'>\n<parameter name='z'/>\n</subsystem>\n");
  Write("outer.xml", "<subsystem name='outer'>\n<blocks>\n<block type='subsystem' name='i' src='inner.xml'>\n"
                     "<param name='z' value='10+index'/>\n</block>\n</blocks>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='o' src='outer.xml' count='2'/>\n");
  const LoadedDiagram d = Load();
  EXPECT_EQ(Value(d, "o[1].i.z"), 11);
  EXPECT_EQ(Value(d, "o[0].i.z"), 10);
}

// --- tracebacks -------------------------------------------------------------------------

TEST_F(InstancesTest, ErrorInsideAnInstanceNamesEveryIncludingLine) {
  Write("inner.xml", "<subsystem name='inner'>\n<parameter name='z'/>\n<identifiers>\n"
                     "<identifier name='bad' value='z+nonsense'/>\n</identifiers>\n</subsystem>\n");
  Write("outer.xml", "<subsystem name='outer'>\n<blocks>\n<block type='subsystem' name='i' src='inner.xml'>\n"
                     "<param name='z' value='1'/>\n</block>\n</blocks>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='o' src='outer.xml' count='3'/>\n");
  EXPECT_THAT(Error(), StartsWith("inner.xml:4: in o[0].i (outer.xml:3, main.xml:5)"));
}

TEST_F(InstancesTest, ErrorOfABlockInAnArrayElementNamesIt) {
  Write("p.xml", "<subsystem name='p'>\n<parameter name='k' default='1'/>\n<blocks>\n"
                 "<block type='gain' name='g' k='1/(k-index)'/>\n</blocks>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='s' src='p.xml' count='3'/>\n");
  EXPECT_THAT(Error(), StartsWith("p.xml:4: in s[1] (main.xml:5): block 's[1].g' parameter 'k': "));
}

// The command line: --set of an element's parameter, and check listing the paths.
TEST_F(InstancesTest, SetOnTheCommandLine) {
  Write("p.xml", "<subsystem name='p'>\n<parameter name='k' default='2'/>\n<identifiers>\n"
                 "<identifier name='k2' value='k*k'/>\n</identifiers>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='d' src='p.xml' count='2'/>\n<block type='clock' name='c'/>\n");
  const auto run = testing::RunMechflow("check " + Path("main.xml") + " --set 'd[1].k=3'");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("d[1].k2 = 9"));
  EXPECT_THAT(run.out, HasSubstr("d[0].k2 = 4"));
  const auto derived = testing::RunMechflow("check " + Path("main.xml") + " --set 'd[1].k2=3'");
  EXPECT_EQ(derived.exit_code, 2);
  EXPECT_THAT(derived.err, HasSubstr("d[1].k2"));
}

TEST_F(InstancesTest, ErrorInANestedParamCarriesTheInstance) {
  Write("inner.xml", "<subsystem name='inner'>\n<parameter name='z'/>\n</subsystem>\n");
  Write("outer.xml", "<subsystem name='outer'>\n<blocks>\n<block type='subsystem' name='i' src='inner.xml'>\n"
                     "<param name='zz' value='1'/>\n</block>\n</blocks>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='o' src='outer.xml' count='2'/>\n");
  EXPECT_THAT(Error(), StartsWith("outer.xml:4: in o[0] (main.xml:5): subsystem 'inner'"));
  Write("outer.xml", "<subsystem name='outer'>\n<blocks>\n<block type='subsystem' name='i' src='inner.xml' "
                     "count='0'/>\n</blocks>\n</subsystem>\n");
  EXPECT_THAT(Error(), StartsWith("outer.xml:3: in o[0] (main.xml:5): count"));
}


// Words among block parameters (files, port names, kinds) are no expressions: neither renamed as the
// instance's parameters nor refused as the diagram's identifiers.
TEST_F(InstancesTest, WordParametersOfBlocksStayAsWritten) {
  Write("road.csv", "t,y\n0,1\n10,1\n");
  Write("p.xml", "<subsystem name='p'>\n<parameter name='cubic' default='1'/>\n<output name='y'/>\n<output name='z'/>\n"
                 "<blocks>\n<block type='table' name='tb' file='road.csv'/>\n"
                 "<block type='lookup' name='lk' points='0 0; 1 cubic; 2 4; 3 9' interpolation='cubic'/>\n</blocks>\n"
                 "<connections>\n<connect from='tb.y' to='y'/>\n<connect from='tb.y' to='lk.u'/>\n"
                 "<connect from='lk.y' to='z'/>\n</connections>\n</subsystem>\n");
  WriteMain("<identifier name='road' value='2'/>\n",
            "<block type='subsystem' name='d' src='p.xml'/>\n<block type='gain' name='g' k='1'/>\n"
            "<block type='gain' name='h' k='1'/>\n",
            "<connect from='d.y' to='g.u'/>\n<connect from='d.z' to='h.u'/>\n",
            "<output>\n<log signal='g.y' label='y'/>\n<log signal='h.y' label='z'/>\n</output>\n");
  EXPECT_NEAR(Final("y"), 1, 1e-12);
  EXPECT_NEAR(Final("z"), 1, 1e-12);
}

// --- mechanisms in subsystems ----------------------------------------------------------

// A body of mass `mass` pushed by the force at input u: y = its position.
const char* kPushed =
    "<subsystem name='pushed'>\n"
    "<parameter name='mass' default='1' unit='kg'/>\n"
    "<parameter name='force' default='0' unit='N'/>\n"
    "<input name='u'/>\n<output name='y'/>\n"
    "<mechanism name='m' gravity='0 0 0'>\n"
    "  <input name='force'/>\n"
    "  <body name='B' mass='mass' inertia='1 1 1'/>\n"
    "  <joint name='x' type='translational' body1='Base0' body2='B' axis='1 0 0'/>\n"
    "  <applied_force name='push' body='B' force='force 0 0'/>\n"
    "  <sensor name='pos' kind='coordinate' dof='x'/>\n"
    "</mechanism>\n"
    "<connections>\n<connect from='u' to='m.force'/>\n<connect from='m.pos' to='y'/>\n</connections>\n"
    "</subsystem>\n";

TEST_F(InstancesTest, ArrayOfSubsystemsHoldingMechanismsFedThroughPorts) {
  Write("pushed.xml", kPushed);
  WriteMain("", "<block type='subsystem' name='d' src='pushed.xml' count='2'>\n<param name='mass' value='1+index'/>\n"
                "</block>\n<block type='constant' name='one' value='1'/>\n"
                "<block type='gain' name='y0' k='1'/>\n<block type='gain' name='y1' k='1'/>\n",
            "<connect from='one.y' to='d[0].u'/>\n<connect from='one.y' to='d[1].u'/>\n"
            "<connect from='d[0].y' to='y0.u'/>\n<connect from='d[1].y' to='y1.u'/>\n",
            "<output>\n<log signal='y0.y' label='y0'/>\n<log signal='y1.y' label='y1'/>\n</output>\n");
  EXPECT_NEAR(Final("y0"), 0.5, 1e-6);
  EXPECT_NEAR(Final("y1"), 0.25, 1e-6);
}

TEST_F(InstancesTest, MechanismInputMustNameAParameter) {
  std::string text = kPushed;
  text.replace(text.find("<input name='force'/>"), 21, "<input name='forse'/>");
  Write("pushed.xml", text);
  WriteMain("", "<block type='subsystem' name='d' src='pushed.xml'/>\n");
  EXPECT_THAT(Error(), StartsWith("pushed.xml:7: in d (main.xml:5): input 'forse' must name a parameter or "
                                  "identifier of subsystem 'pushed'"));
}

// The lead wires input widths into the loader: until then a width= is
// checked as a number only, and a wider signal is accepted (today's behaviour).
TEST_F(InstancesTest, InputWidthCheckedAsANumber) {
  Write("p.xml", "<subsystem name='p'>\n<input name='u' width='two'/>\n</subsystem>\n");
  WriteMain("", "<block type='subsystem' name='d' src='p.xml'/>\n");
  EXPECT_THAT(Error(), StartsWith("p.xml:2: in d (main.xml:5): input 'u' width is 'two'; expected a whole number >= 1"));
}

// --- parts ----------------------------------------------------------------------------

// A wagon on a rail, coupled by a spring to the body `prev` is.
const char* kWagon =
    "<part name='wagon'>\n"                                                                       // 1
    "<parameter name='x0' default='0' unit='m'/>\n"                                               // 2
    "<attach name='prev'/>\n"                                                                     // 3
    "<body name='Box' mass='1' inertia='1 1 1'>\n<point name='hook' at='0.5 0 0'/>\n</body>\n"    // 4-6
    "<joint name='x' type='translational' body1='Base0' body2='Box' axis='1 0 0' q0='x0'/>\n"     // 7
    "<force name='coupler' type='linear' body1='prev' body2='Box' point2='hook' c='100'/>\n"      // 8
    "<sensor name='pos' kind='coordinate' dof='x'/>\n"                                            // 9
    "</part>\n";

// main.xml with the mechanism `m`: the body Loco on a rail, then `elements` (from line 11 with one identifier).
class PartsTest : public InstancesTest {
 protected:
  void WriteTrain(const std::string& elements, const std::string& identifiers = "<identifier name='n' value='3'/>\n") {
    Write("wagon.xml", kWagon);
    WriteMain(identifiers, "",  "",
              "<mechanism name='m' gravity='0 0 0'>\n"
              "<body name='Loco' mass='1' inertia='1 1 1'/>\n"
              "<joint name='loco' type='translational' body1='Base0' body2='Loco' axis='1 0 0'/>\n" +
                  elements + "</mechanism>\n");
  }
  // The flattened element `name` of mechanism m.
  static const ElementDesc* Element(const LoadedDiagram& d, const std::string& name) {
    for (const ElementDesc& e : d.description.mechanisms.at(0).children)
      if (e.Text("name") == name) return &e;
    return nullptr;
  }
};

TEST_F(PartsTest, ElementsAndReferencesPrefixedAttachPointsReplaced) {
  WriteTrain("<include part='wagon.xml' name='w' count='n' first='prev=Loco' attach='prev=w[index-1].Box'>\n"
             "<param name='x0' value='-2*(index+1)'/>\n</include>\n");
  const LoadedDiagram d = Load();
  EXPECT_EQ(Value(d, "m.w[2].x0"), -6);
  ASSERT_NE(Element(d, "w[2].Box"), nullptr);
  EXPECT_EQ(Element(d, "w[2].x")->Text("body2"), "w[2].Box");
  EXPECT_EQ(Element(d, "w[2].x")->Text("body1"), "Base0");
  EXPECT_EQ(Element(d, "w[2].coupler")->Text("body1"), "w[1].Box");
  EXPECT_EQ(Element(d, "w[0].coupler")->Text("body1"), "Loco");
  EXPECT_EQ(Element(d, "w[2].pos")->Text("dof"), "w[2].x");
  EXPECT_EQ(Element(d, "w[2].Box")->children.at(0).Text("name"), "hook");
  // given by an expression (of index): derived, not set
  EXPECT_THAT(ErrorOf(Setting({{"m.w[1].x0", 7}})),
              StartsWith("--set m.w[1].x0: identifier 'm.w[1].x0' is defined by an expression"));
}

TEST_F(PartsTest, SensorsOfPartsAreLogged) {
  WriteTrain("<include part='wagon.xml' name='w' count='2' first='prev=Loco' attach='prev=w[index-1].Box'>\n"
             "<param name='x0' value='-2*(index+1)'/>\n</include>\n");
  std::string text = testing::ReadFile(dir_ / "main.xml");
  text.replace(text.find("<solver"), 0, "<output>\n<log signal='m.w[1].pos' label='w1'/>\n</output>\n");
  Write("main.xml", text);
  EXPECT_NEAR(Final("w1"), -4, 1e-9);  // at rest: the couplers are free at the start
}

TEST_F(PartsTest, EveryElementsSensorConnectedAtOnce) {
  WriteTrain("<include part='wagon.xml' name='w' count='2' first='prev=Loco' attach='prev=w[index-1].Box'>\n"
             "<param name='x0' value='-2*(index+1)'/>\n</include>\n");
  Write("p.xml", "<subsystem name='p'>\n<input name='u'/>\n<output name='y'/>\n<blocks><block type='gain' name='g' "
                 "k='1'/></blocks>\n<connections><connect from='u' to='g.u'/><connect from='g.y' to='y'/>"
                 "</connections>\n</subsystem>\n");
  std::string text = testing::ReadFile(dir_ / "main.xml");
  text.replace(text.find("<solver"), 0,
               "<blocks><block type='subsystem' name='g' src='p.xml' count='2'/></blocks>\n"
               "<connections><connect from='m.w[*].pos' to='g[*].u'/></connections>\n"
               "<output>\n<log signal='g[1].y' label='w1'/>\n</output>\n");
  Write("main.xml", text);
  EXPECT_NEAR(Final("w1"), -4, 1e-9);
}

TEST_F(PartsTest, ForceOfTheMechanismJoinsBodiesOfTwoInstances) {
  WriteTrain("<include part='wagon.xml' name='a' attach='prev=Loco'/>\n"
             "<include part='wagon.xml' name='b' attach='prev=Loco'/>\n"
             "<force name='link' type='linear' body1='a.Box' body2='b.Box' point1='hook' c='5'/>\n");
  const LoadedDiagram d = Load();
  EXPECT_EQ(Element(d, "link")->Text("body1"), "a.Box");
  EXPECT_EQ(Element(d, "link")->Text("point1"), "hook");
}

TEST_F(PartsTest, AttachProblemsRefused) {
  const std::pair<std::string, std::string> cases[] = {
      {"<include part='wagon.xml' name='w'/>",
       "main.xml:12: m.w does not say which body its attach point 'prev' is (wagon.xml:3); add attach=\"prev=BODY\""},
      {"<include part='wagon.xml' name='w' attach='pref=Loco'/>",
       "main.xml:12: attach 'pref=Loco' of m.w: part 'wagon' (wagon.xml) has no attach point 'pref' (did you mean "
       "'prev'?); its attach points: prev"},
      {"<include part='wagon.xml' name='w' attach='prev=Loco prev=Loco'/>",
       "main.xml:12: attach 'prev=Loco' of m.w: attach point 'prev' is given twice"},
      {"<include part='wagon.xml' name='w' first='prev=Loco' attach='prev=Loco'/>",
       "main.xml:12: first= gives the attach of name[0] of an array; add count="},
      {"<include part='wagon.xml' name='w' count='2' attach='prev=w[index-1].Box'/>",
       "main.xml:12: attach 'prev=w[index-1].Box' of m.w[0]: the index [index-1] is -1; expected a whole number >= 0"},
      // said at the include, not in the part where the body is used
      {"<include part='wagon.xml' name='w' attach='prev=Lcoo'/>",
       "main.xml:12: attach 'prev=Lcoo' of m.w: mechanism 'm' has no body 'Lcoo' (did you mean 'Loco'?)"},
  };
  for (const auto& [include, expected] : cases) {
    SCOPED_TRACE(include);
    WriteTrain(include + "\n");
    EXPECT_THAT(Error(), StartsWith(expected));
  }
}

TEST_F(PartsTest, NamesOfIncludesTakenTwiceRefused) {
  WriteTrain("<include part='wagon.xml' name='w' attach='prev=Loco'/>\n"
             "<include part='wagon.xml' name='w' attach='prev=Loco'/>\n");
  EXPECT_THAT(Error(), StartsWith("main.xml:13: include name 'w' is used twice (first at main.xml:12)"));
}

TEST_F(PartsTest, NestedPartsPrefixedTwice) {
  Write("train.xml", "<part name='train'>\n<attach name='head'/>\n<parameter name='n' default='2'/>\n"
                     "<include part='wagon.xml' name='w' count='n' first='prev=head' attach='prev=w[index-1].Box'/>\n"
                     "</part>\n");
  WriteTrain("<include part='train.xml' name='t' attach='head=Loco'/>\n");
  const LoadedDiagram d = Load();
  EXPECT_EQ(Element(d, "t.w[1].coupler")->Text("body1"), "t.w[0].Box");
  EXPECT_EQ(Element(d, "t.w[0].coupler")->Text("body1"), "Loco");
  EXPECT_EQ(Value(d, "m.t.w[1].x0"), 0);
  EXPECT_EQ(Value(Load(Setting({{"m.t.w[1].x0", 7}})), "m.t.w[1].x0"), 7);
}

// A point named like an identifier of the diagram is still the point.
TEST_F(PartsTest, PointNamedLikeADiagramIdentifier) {
  WriteTrain("<include part='wagon.xml' name='w' attach='prev=Loco'/>\n", "<identifier name='hook' value='1'/>\n");
  EXPECT_EQ(Element(Load(), "w.coupler")->Text("point2"), "hook");
}

TEST_F(PartsTest, ErrorInsideAPartNamesTheInstance) {
  std::string wagon = kWagon;
  wagon.replace(wagon.find("c='100'"), 7, "c='100*nonsense'");
  WriteTrain("<include part='wagon.xml' name='w' count='3' first='prev=Loco' attach='prev=w[index-1].Box'/>\n");
  Write("wagon.xml", wagon);
  EXPECT_THAT(Error(), StartsWith("wagon.xml:8: in m.w[0] (main.xml:12)"));
}

}  // namespace
}  // namespace mechflow::diagrams
