// Reading and loading diagrams: every kind of bad input gives one clear
// message with file:line, and good input is loaded as written.

#include <cstdio>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "diagrams/xml_reader.h"
#include "tests/test_util.h"

namespace mechflow::diagrams {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;
using mechflow::testing::InputErrorOf;
using mechflow::testing::LoadXml;

std::string ErrorOf(const std::string& xml, const LoadOptions& options = {}) {
  return InputErrorOf([&] { LoadXml(xml, options); });
}

// A valid two-block diagram: x' = k * x, with `extra` inserted in <blocks>.
std::string Valid(const std::string& solver = "<solver t_end='1'/>", const std::string& extra = "",
                  const std::string& more_connections = "") {
  return "<diagram name='ok'>\n"                                          // 1
         "<identifiers>\n"                                                // 2
         "  <identifier name='k' value='-2'/>\n"                          // 3
         "</identifiers>\n"                                               // 4
         "<blocks>\n"                                                     // 5
         "  <block type='integrator' name='x' initial='1'/>\n"            // 6
         "  <block type='gain' name='g' k='k'/>\n" +                      // 7
         extra +
         "</blocks>\n"
         "<connections>\n"
         "  <connect from='x.y' to='g.u'/>\n"
         "  <connect from='g.y' to='x.u'/>\n" +
         more_connections + "</connections>\n" + solver + "\n</diagram>\n";
}

TEST(XmlReaderTest, MalformedXmlGivesItsLine) {
  // in words, naming what the parser names, without its error codes
  const std::string unclosed = ErrorOf("<diagram>\n<blocks>\n<block type='gain' name='g' k='1'>\n</blocks>\n</diagram>");
  EXPECT_THAT(unclosed, AllOf(StartsWith("test.xml:"), HasSubstr("malformed XML: an element not closed"),
                              HasSubstr("name=block"), Not(HasSubstr("XML_ERROR")), Not(HasSubstr("ErrorID"))));
  EXPECT_THAT(ErrorOf("<diagram>\n\n<blocks name='a' name='b'/></diagram>"),
              StartsWith("test.xml:3: malformed XML: an attribute that does not parse"));
}

// tinyxml2 accepts these; mechflow refuses each at its line.
TEST(XmlReaderTest, RefusesWhatTheXmlParserWouldLetThrough) {
  EXPECT_THAT(ErrorOf("<diagram/>\n<diagram/>"),
              StartsWith("test.xml:2: a second top-level element <diagram>; a file holds one <diagram> element"));
  EXPECT_THAT(ErrorOf("<diagram>\n<identifiers><identifier name='a' value='&foo;'/></identifiers></diagram>"),
              StartsWith("test.xml:2: the undefined entity '&foo;'; expected &amp; &lt; &gt; &quot; &apos;"));
  EXPECT_THAT(ErrorOf("<diagram name='a & b'/>"), StartsWith("test.xml:1: an '&' that starts no reference"));
  EXPECT_THAT(ErrorOf("<?xml version='1.0'?>\n<!DOCTYPE d [<!ENTITY e 'x'>]>\n<diagram name='&e;'/>"),
              StartsWith("test.xml:2: a DOCTYPE declaration; diagrams take none"));
  EXPECT_THAT(ErrorOf("<diagram>\n\n<blocks><block type='gain' name='g\xe9' k='1'/></blocks></diagram>"),
              StartsWith("test.xml:3: the byte 0xE9 is not UTF-8; save the file as UTF-8"));
  EXPECT_THAT(ErrorOf("<diagram name='\xc0\xaf'/>"), HasSubstr("the byte 0xC0 is not UTF-8"));  // overlong '/'
  EXPECT_THAT(ErrorOf("<diagram name='a\x01'/>"), HasSubstr("the control character U+0001 is not allowed"));
  EXPECT_THAT(ErrorOf("<diagram name='a&#0;'/>"), HasSubstr("'&#0;' names a character XML does not allow"));
  EXPECT_THAT(ErrorOf("<diagram name='a&#xZZ;'/>"), HasSubstr("'&#xZZ;' is not a number"));
  EXPECT_THAT(ErrorOf("<diagram>\n<!-- never closed\n</diagram>"), StartsWith("test.xml:2: a comment that is never closed"));
  // what XML allows still reads
  EXPECT_EQ(LoadXml("<diagram name='&#955;&amp;&#x3bb;'><!-- & --></diagram>").description.name, "\u03bb&\u03bb");
}

TEST(XmlReaderTest, UnknownElementsAndAttributesSuggestTheNearestName) {
  EXPECT_THAT(ErrorOf("<diagram>\n<blokcs/>\n</diagram>"),
              AllOf(StartsWith("test.xml:2: unknown element <blokcs> inside <diagram> (did you mean 'blocks'?)"),
                    HasSubstr("expected one of: identifiers, input, variants, mechanism, blocks")));
  EXPECT_THAT(ErrorOf("<diagram>\n<solver t_edn='1'/>\n</diagram>"),
              StartsWith("test.xml:2: <solver> has no attribute 't_edn' (did you mean 't_end'?)"));
  EXPECT_THAT(ErrorOf("<diagram><identifiers>\n<identifier name='a' valeu='1'/></identifiers></diagram>"),
              StartsWith("test.xml:2: <identifier> has no attribute 'valeu' (did you mean 'value'?)"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/>", "  <block type='gain' name='h' kk='1'/>\n")),
              StartsWith("test.xml:8: block 'h' (gain) has no parameter 'kk' (did you mean 'k'?)"));
  EXPECT_THAT(ErrorOf("<diagram><connections>\n<connect from='a.y'/></connections></diagram>"),
              StartsWith("test.xml:2: <connect> needs the attribute 'to'"));
  EXPECT_THAT(ErrorOf("<model/>"), HasSubstr("the top element is <model>; expected <diagram>"));
  EXPECT_THAT(ErrorOf("<diagram><solver/>\n<solver/></diagram>"), StartsWith("test.xml:2: a second <solver>"));
}

TEST(LoaderTest, UnknownBlockTypeListsTheKnownOnes) {
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/>", "  <block type='gian' name='h' k='1'/>\n")),
              AllOf(StartsWith("test.xml:8: block 'h' has unknown type 'gian' (did you mean 'gain'?)"),
                    HasSubstr("known types: abs, clock, constant")));
}

TEST(LoaderTest, BadNumbersAreReportedWithTheirAttribute) {
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1' rtol='1e-6x'/>")),
              AllOf(StartsWith("test.xml:"), HasSubstr("solver setting 'rtol': '1e-6x' is not a valid expression")));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/>", "  <block type='gain' name='h' k='2..5'/>\n")),
              AllOf(StartsWith("test.xml:8: block 'h' parameter 'k'"), HasSubstr("not a valid expression")));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/>", "  <block type='gain' name='h' k='kk'/>\n")),
              HasSubstr("unknown name 'kk' (did you mean 'k'?)"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/>", "  <block type='gain' name='h' k=''/>\n")),
              HasSubstr("expected a number or an expression, found nothing"));
}

TEST(LoaderTest, MissingReferencedFile) {
  const std::string path = ::testing::TempDir() + "/mechflow_missing_file.xml";
  {
    std::ofstream f(path);
    f << Valid("<solver t_end='1'/>", "  <block type='table' name='tab' file='nope.csv'/>\n");
  }
  const std::string error = InputErrorOf([&] { LoadDiagram(path); });
  EXPECT_THAT(error, AllOf(HasSubstr("mechflow_missing_file.xml:8: block 'tab' parameter 'file': file 'nope.csv' "
                                     "not found")));
  std::remove(path.c_str());
  EXPECT_THAT(InputErrorOf([&] { LoadDiagram(path); }), HasSubstr("cannot open diagram file"));
}

TEST(LoaderTest, IdentifierErrors) {
  const std::string below =
      "<diagram><identifiers>\n<identifier name='a' value='b*2'/>\n<identifier name='b' value='1'/>\n"
      "</identifiers></diagram>";
  EXPECT_THAT(ErrorOf(below), StartsWith("test.xml:2: identifier 'a': uses 'b', which is defined below it "
                                         "(at test.xml:3)"));
  const std::string cycle =
      "<diagram><identifiers>\n<identifier name='a' value='b'/>\n<identifier name='b' value='a'/>\n"
      "</identifiers></diagram>";
  EXPECT_THAT(ErrorOf(cycle), HasSubstr("which is defined below it"));
  EXPECT_THAT(ErrorOf("<diagram><identifiers>\n<identifier name='a' value='(1 +'/></identifiers></diagram>"),
              AllOf(StartsWith("test.xml:2: identifier 'a': '(1 +' is not a valid expression"),
                    HasSubstr("unexpected symbol")));
}

TEST(LoaderTest, LuaExpressionSyntaxErrorNamesTheBlock) {
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/>", "  <block type='expression' name='f' expr='u +* 2'/>\n")),
              AllOf(StartsWith("test.xml:8: block 'f' (expression): expression 'u +* 2' does not compile"),
                    HasSubstr("block 'f':1: unexpected symbol near '*'")));
}

TEST(LoaderTest, SchedulerErrorsNameBothEnds) {
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/>", "  <block type='gain' name='h' k='1'/>\n")),
              StartsWith("test.xml:8: input h.u is not connected"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/>", "", "  <connect from='x.y' to='x.u'/>\n")),
              AllOf(StartsWith("test.xml:12: input x.u is driven twice: by g.y (test.xml:11) and by x.y"),
                    HasSubstr("use a sum block")));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/>", "  <block type='constant' name='c' value='1 2'/>\n"
                                                   "  <block type='gain' name='h' k='1'/>\n",
                            "  <connect from='c.y' to='h.u'/>\n")),
              HasSubstr("connection from 'c.y' to 'h.u': width mismatch: output c.y has width 2, input h.u has width 1"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/>", "", "  <connect from='x.y' to='g.in'/>\n")),
              AllOf(HasSubstr("connection from 'x.y' to 'g.in': block 'g' (gain) has no input port 'in'"), HasSubstr("its inputs: u")));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/>", "", "  <connect from='xx.y' to='g.u'/>\n")),
              HasSubstr("there is no block named 'xx' (did you mean 'x'?)"));
  // gain -> sum -> gain, all with direct feedthrough
  const std::string loop = Valid("<solver t_end='1'/>",
                                 "  <block type='gain' name='a' k='1'/>\n  <block type='sum' name='s'/>\n"
                                 "  <block type='constant' name='c' value='1'/>\n",
                                 "  <connect from='a.y' to='s.u1'/>\n  <connect from='c.y' to='s.u2'/>\n"
                                 "  <connect from='s.y' to='a.u'/>\n");
  // a loop is no load error: it is solved at run time (this one has no
  // solution, which the run reports), and its hops name where it was wired
  const LoadedDiagram looped = LoadXml(loop);
  ASSERT_EQ(looped.diagram->loops().size(), 1u);
  EXPECT_THAT(looped.diagram->loops()[0].description(),
              AllOf(HasSubstr("a.y -> s.u1 (feeds s.y directly) at test.xml:"),
                    HasSubstr("s.y -> a.u (feeds a.y directly) at test.xml:")));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/>", "  <block type='gain' name='g' k='1'/>\n")),
              HasSubstr("block name 'g' is used twice (first at test.xml:7)"));
}

TEST(LoaderTest, SolverSettingsAreChecked) {
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='0'/>")),
              HasSubstr("t_end = 0 s: it must be a finite number greater than t_start = 0 s"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='-1'/>")), HasSubstr("t_end = -1 s: it must be a finite number greater"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='math.huge'/>")), HasSubstr("'math.huge' gives inf"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1' rtol='2'/>")), HasSubstr("rtol = 2: it must be at least 1e-15 (double precision cannot follow a tighter one) and < 1"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1' rtol='1e-300'/>")), HasSubstr("it must be at least 1e-15"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1' rtol='-1e-6'/>")), HasSubstr("it must be at least 1e-15"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1' atol='-1'/>")), HasSubstr("atol = -1: it must be a finite number > 0"));
  LoadOptions options;
  options.t_end = -3;  // the run's value is to blame, not a line of the file
  EXPECT_THAT(ErrorOf(Valid(), options),
              StartsWith("the run's own solver settings (--t-end, --rtol, --atol; run()'s t_end, rtol, atol): t_end = -3 s"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1' atol='-1'/>"), options),  // the file's own first, at its line
              AllOf(StartsWith("test.xml:"), HasSubstr("atol = -1: it must be")));
}

// Values that once passed and failed late (or were undefined behaviour):
// each is refused at its line.
TEST(LoaderTest, CountsAndIntervalsAreChecked) {
  const char* whole = "; expected a whole number from 1 to 1e12";
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1' max_steps='1.5'/>")), HasSubstr("max_steps' is 1.5" + std::string(whole)));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1' max_steps='1e30'/>")), HasSubstr("is 1e30" + std::string(whole)));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1' max_steps='0'/>")), HasSubstr(whole));
  EXPECT_EQ(LoadXml(Valid("<solver t_end='1' max_steps='1e6'/>")).solver.max_steps, 1000000);
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/><output><log signal='x.y' label='time'/></output>")),
              HasSubstr("a logged column named 'time', which is the name of the first column"));
  EXPECT_THAT(ErrorOf(Valid("<output interval='0'/>")),
              HasSubstr("output setting 'interval' is 0; expected a time > 0 s (leave it out for 1000 rows)"));
  EXPECT_THAT(ErrorOf(Valid("<output interval='-1'/>")), HasSubstr("expected a time > 0 s"));
  EXPECT_THAT(ErrorOf(Valid("<output interval='1e-300'/>")),
              HasSubstr("output interval: the period 1e-300 s is too small for the run from t = 0 to 1 s"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_start='1e10' t_end='1e10+1'/><output interval='1e-5'/>")),
              HasSubstr("cannot be told apart in double precision"));
  // a sampled block whose period the run could never get through: refused where the run is set up
  const auto sampled = [](const std::string& period) {
    return InputErrorOf([&] {
      mechflow::testing::RunXml(Valid("<solver t_end='1'/>", "  <block type='sample_hold' name='h' period='" +
                                                                 period + "'/>\n",
                                      "  <connect from='x.y' to='h.u'/>\n"));
    });
  };
  EXPECT_THAT(sampled("1e-300"), HasSubstr("test.xml:8: block 'h': sample period: the period 1e-300 s is too small for the run "
                                           "from t = 0 to 1 s (more than 1e8 instants in the run); use at least 1e-08 s"));
  EXPECT_EQ(sampled("1e-3"), "");
}

TEST(LoaderTest, SetOverridesOnlyNumbers) {
  LoadOptions options;
  options.overrides = {{"K", -3}};
  const LoadedDiagram loaded = LoadXml(Valid(), options);
  EXPECT_EQ(loaded.identifiers->Value("k"), -3);
  options.overrides = {{"kay", 1}};
  EXPECT_THAT(ErrorOf(Valid(), options), HasSubstr("--set kay: no identifier named 'kay'"));
  const std::string derived = "<diagram><identifiers><identifier name='a' value='1'/>"
                              "<identifier name='b' value='2*a'/></identifiers></diagram>";
  options.overrides = {{"b", 1}};
  EXPECT_THAT(ErrorOf(derived, options), HasSubstr("--set b: identifier 'b' is defined by an expression"));
}

TEST(LoaderTest, OutputsLogsGroupsAndRecorders) {
  const LoadedDiagram loaded = LoadXml(Valid("<solver t_end='2' rtol='1e-9'/>\n"
                                             "<output interval='0.5' plot='p.svg'>\n"
                                             "  <log signal='x' label='position' group='state'/>\n"
                                             "  <log signal='g.y' label='rate' group='state'/>\n"
                                             "</output>",
                                             "  <block type='recorder' name='rec' inputs='2'/>\n",
                                             "  <connect from='x.y' to='rec.u1'/>\n  <connect from='g.y' to='rec.u2'/>\n"));
  EXPECT_EQ(loaded.solver.t_end, 2);
  EXPECT_EQ(loaded.solver.rtol, 1e-9);
  EXPECT_EQ(loaded.solver.output_interval, 0.5);
  EXPECT_EQ(loaded.csv_file, "ok.csv");
  EXPECT_EQ(loaded.plot_file, "p.svg");
  ASSERT_EQ(loaded.logged.size(), 4u);
  EXPECT_EQ(loaded.logged[0].name, "position");
  EXPECT_EQ(loaded.logged[1].name, "rate");
  EXPECT_EQ(loaded.logged[2].name, "x.y");
  EXPECT_EQ(loaded.logged[3].name, "g.y");
  ASSERT_EQ(loaded.groups.size(), 2u);
  EXPECT_EQ(loaded.groups[0].name, "state");
  EXPECT_EQ(loaded.groups[0].columns, (std::vector<int>{1, 2}));
  EXPECT_EQ(loaded.groups[1].name, "rec");
  EXPECT_EQ(loaded.groups[1].columns, (std::vector<int>{3, 4}));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/><output><log signal='x'/><log signal='x.y'/></output>")),
              HasSubstr("a second logged column named 'x.y'"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/><output><log signal='x.z'/></output>")),
              HasSubstr("<log>: signal 'x.z': block 'x' has no output 'z'"));
  EXPECT_THAT(ErrorOf(Valid("<solver t_end='1'/><output plot='p.jpg'/>")), HasSubstr("must end in .png or .svg"));
}

}  // namespace
}  // namespace mechflow::diagrams
