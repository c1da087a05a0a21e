// A diagram from someone else, run as a user would run it: it cannot run a
// command through the plot script, cannot write outside the output folder,
// cannot make a file format say what it likes, cannot hang the run on a
// file that never ends, and a file that could not be written is a failure
// that says what was and was not written.

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "blocks/outputs/results.h"
#include "cli/output_folder.h"
#include "cli/plot.h"
#include "cli/results_file.h"
#include "cli/xy_plot.h"
#include "tests/cli/mechflow_command.h"

namespace mechflow::cli {
namespace {

namespace fs = std::filesystem;
using mechflow::testing::ReadFile;
using mechflow::testing::RunMechflow;
using ::testing::HasSubstr;

class HostileDiagramTest : public ::testing::Test {
 protected:
  HostileDiagramTest() {
    dir_ = fs::path(::testing::TempDir()) / ("mechflow_hostile_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "out");
  }
  ~HostileDiagramTest() override { fs::remove_all(dir_); }

  // Writes a diagram with `name`, `output` attributes and a log label; returns its path.
  std::string Diagram(const std::string& name, const std::string& output, const std::string& label = "x",
                      const std::string& group = "g") {
    const fs::path path = dir_ / "d.xml";
    std::ofstream(path) << "<diagram name=\"" << name << "\">\n"
                        << "<blocks><block type=\"constant\" name=\"c\" value=\"1\"/></blocks>\n"
                        << "<solver t_end=\"1\"/>\n"
                        << "<output interval=\"0.5\" " << output << ">\n"
                        << "  <log signal=\"c.y\" label=\"" << label << "\" group=\"" << group << "\"/>\n"
                        << "</output>\n</diagram>\n";
    return path.string();
  }
  std::string Out() const { return (dir_ / "out").string(); }
  fs::path dir_;
};

// What a hostile text tries in the gnuplot script: end the string, end the
// line, and call system().
const std::string kMarker = "mechflow_hostile_marker";

TEST_F(HostileDiagramTest, NoTextReachesGnuplotAsACommand) {
  const std::string marker = (dir_ / kMarker).string();
  // quotes, backslashes, backquotes and system(...) in every text field: drawn, not run
  const std::string text = "q&apos;&quot;\\ `touch " + marker + "` system(&apos;touch " + marker + "&apos;)";
  const auto run = RunMechflow("run " + Diagram(text, "csv=\"r.csv\" plot=\"r.png\"", text, text) + " --out " + Out());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "r.png"));
  EXPECT_FALSE(fs::exists(marker));
  // a line break in any of them is refused at its line, before anything is written
  for (const std::string& attributes : {std::string("name=\"a&#10;system('touch ") + marker + "')\""}) {
    const fs::path path = dir_ / "nl.xml";
    std::ofstream(path) << "<diagram " << attributes << "/>\n";
    const auto refused = RunMechflow("run " + path.string() + " --out " + Out());
    EXPECT_EQ(refused.exit_code, 2);
    EXPECT_THAT(refused.err, HasSubstr("nl.xml:1: <diagram> name= holds a line break or another control character"));
  }
  for (const char* field : {"label", "group"}) {
    const std::string nl = "a&#10;system(&apos;touch " + marker + "&apos;)";
    const auto refused = RunMechflow("run " + Diagram("d", "plot=\"p.png\"", field == std::string("label") ? nl : "x",
                                                      field == std::string("group") ? nl : "g") +
                                     " --out " + Out());
    EXPECT_EQ(refused.exit_code, 2) << field;
    EXPECT_THAT(refused.err, HasSubstr(std::string("d.xml:5: <log> ") + field + "= holds a line break")) << field;
  }
  EXPECT_FALSE(fs::exists(marker));
}

// The script itself, given line breaks directly (as no diagram can give
// them): every text stays inside its string.
TEST_F(HostileDiagramTest, TheGnuplotScriptKeepsEveryTextOnItsLine) {
  const std::string marker = (dir_ / kMarker).string();
  const std::string attack = "x'\n!touch " + marker + "\nsystem('touch " + marker + "')\r\n'";
  blocks::Results results({attack});
  const double row[] = {0.0, 1.0};
  results.AddRow(row);
  const OutputFolder folder(Out());
  std::ostringstream csv;
  results.WriteCsv(csv);
  folder.Write("r.csv", csv.str());
  const std::string script = GnuplotScript(results, {{attack, {1}, attack}}, attack, "r.csv", "r.svg");
  for (std::size_t at = script.find("touch"); at != std::string::npos; at = script.find("touch", at + 1)) {
    const std::size_t line = script.rfind('\n', at) + 1;
    EXPECT_EQ(script[script.find_first_not_of(' ', line)] == '!', false) << script;
  }
  EXPECT_EQ(DrawPlot(script, folder, "r.svg"), "");
  EXPECT_FALSE(fs::exists(marker));
  // the CSV header stays one line: the label is quoted
  EXPECT_THAT(csv.str(), ::testing::StartsWith("time,\"x'\n!touch "));
  // the x-y plots (force analysis, spectra) quote their texts alike
  const std::string xy = XYPlotScript({{attack, attack, attack, {{0, 1, attack}}}}, attack, "r.csv", "r2.svg");
  for (std::size_t at = xy.find("touch"); at != std::string::npos; at = xy.find("touch", at + 1)) {
    const std::size_t line = xy.rfind('\n', at) + 1;
    EXPECT_NE(xy[xy.find_first_not_of(' ', line)], '!') << xy;
  }
  EXPECT_EQ(DrawPlot(xy, folder, "r2.svg"), "");
  EXPECT_FALSE(fs::exists(marker));
}

TEST_F(HostileDiagramTest, OutputNamesStayInsideTheOutputFolder) {
  for (const char* output : {"csv=\"../escaped.csv\"", "csv=\"/tmp/escaped.csv\"", "plot=\"/tmp/escaped.png\"",
                                    "plot=\"sub/../../escaped.png\"", "csv=\"..\""}) {
    const auto run = RunMechflow("run " + Diagram("d", output) + " --out " + Out());
    EXPECT_EQ(run.exit_code, 2) << output;
    EXPECT_THAT(run.err, HasSubstr("d.xml:4:")) << output;
    EXPECT_THAT(run.err, ::testing::AnyOf(HasSubstr("must be a plain file name"), HasSubstr("is not a file name")))
        << output;
  }
  const auto named = RunMechflow("run " + Diagram("../../escaped", "") + " --out " + Out());
  EXPECT_EQ(named.exit_code, 2);
  EXPECT_THAT(named.err, HasSubstr("the results file '../../escaped.csv' named after the diagram must be a plain"));
  EXPECT_FALSE(fs::exists(dir_ / "escaped.csv"));
  EXPECT_FALSE(fs::exists(dir_.parent_path() / "escaped.csv"));
}

TEST_F(HostileDiagramTest, ASymbolicLinkInTheOutputFolderIsNotFollowed) {
  const fs::path victim = dir_ / "victim.txt";
  std::ofstream(victim) << "precious\n";
  fs::create_symlink(victim, dir_ / "out" / "r.csv");
  fs::create_symlink(victim, dir_ / "out" / "r.png");
  // the results file is made before the run: bad input, nothing run
  auto run = RunMechflow("run " + Diagram("d", "csv=\"r.csv\" plot=\"r.png\"") + " --out " + Out());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("r.csv': it is a symbolic link, which is not followed"));
  EXPECT_THAT(run.out, ::testing::Not(HasSubstr("finished")));
  EXPECT_EQ(ReadFile(victim), "precious\n");
  // the plot is made after it: reported, the rest written
  fs::remove(dir_ / "out" / "r.csv");
  run = RunMechflow("run " + Diagram("d", "csv=\"r.csv\" plot=\"r.png\"") + " --out " + Out());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.err, HasSubstr("r.png': it is a symbolic link, which is not followed"));
  EXPECT_THAT(run.err, HasSubstr(": written r.csv, r.units.csv; not written r.png\n"));
  EXPECT_EQ(ReadFile(victim), "precious\n");
}

TEST_F(HostileDiagramTest, ABadOutputFolderIsBadInputBeforeTheRun) {
  std::ofstream(dir_ / "file") << "x";
  const auto run = RunMechflow("run " + Diagram("d", "") + " --out " + (dir_ / "file" / "sub").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("cannot create the output folder"));
  EXPECT_THAT(run.out, ::testing::Not(HasSubstr("finished")));
}

TEST_F(HostileDiagramTest, AFullDiskWhileStreamingIsReportedAtTheEnd) {
  if (::access("/dev/full", W_OK) != 0 || ::access("/dev", W_OK) != 0) GTEST_SKIP() << "needs /dev/full";
  const OutputFolder dev("/dev");
  ResultsFile file(dev, "full", {"time", "x"});
  const double row[2] = {0.5, 1.25};
  for (int i = 0; i < 10000; ++i) file.WriteRow(row, 2);  // the buffer fills and fails: no throw into the run
  EXPECT_THAT(file.Close(), HasSubstr("error writing '/dev/full' after 0 bytes: No space left on device; the file is "
                                      "cut there, its rows before are kept"));
  EXPECT_EQ(file.cut_reason(), "No space left on device");
}

TEST_F(HostileDiagramTest, AFullDiskIsAWriteErrorNamingTheFile) {
  if (::access("/dev/full", W_OK) != 0 || ::access("/dev", W_OK) != 0) GTEST_SKIP() << "needs /dev/full";
  const OutputFolder dev("/dev");
  try {
    dev.Write("full", std::string(1 << 16, 'x'));
    FAIL() << "no error";
  } catch (const WriteError& e) {
    EXPECT_THAT(e.what(), HasSubstr("error writing '/dev/full' after 0 of 65536 bytes: No space left on device"));
  }
}

TEST_F(HostileDiagramTest, FilesThatNeverEndAreRefusedAtOnce) {
  const fs::path fifo = dir_ / "fifo.lua";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const fs::path big = dir_ / "big.xml";
  { std::ofstream(big).seekp((64 << 20) + 10) << 'x'; }  // sparse: 64 MiB + 11 bytes
  struct Case {
    std::string args, expected;
  };
  const fs::path script_user = dir_ / "s.xml";
  std::ofstream(script_user) << "<diagram><script src=\"fifo.lua\"/></diagram>\n";
  const fs::path mechanism_user = dir_ / "m.xml";
  std::ofstream(mechanism_user) << "<diagram>\n<mechanism name=\"m\" src=\"/dev/zero\"/></diagram>\n";
  const fs::path block_user = dir_ / "b.xml";
  std::ofstream(block_user) << "<diagram><blocks>\n<block type=\"lua\" name=\"l\" src=\"fifo.lua\"/></blocks></diagram>\n";
  const fs::path table_user = dir_ / "t.xml";
  std::ofstream(table_user) << "<diagram><blocks>\n<block type=\"table\" name=\"t\" file=\"/dev/zero\"/></blocks></diagram>\n";
  for (const Case& c : {Case{"check /dev/zero", "diagram file '/dev/zero' is not a regular file (a device)"},
                        Case{"run /dev/zero --out " + Out(), "diagram file '/dev/zero' is not a regular file"},
                        Case{"check " + block_user.string(), "b.xml:2: block 'l' parameter 'src': file 'fifo.lua' "
                                                             "is not a regular file (a pipe)"},
                        Case{"check " + table_user.string() + " --allow-read /dev",
                             "t.xml:2: block 't' parameter 'file': file '/dev/zero' is not a regular file (a device)"},
                        Case{"check " + dir_.string(), "is not a regular file (a folder)"},
                        Case{"check " + fifo.string(), "is not a regular file (a pipe)"},
                        Case{"check " + big.string(), "has 67108875 bytes; input files may have at most 64 MiB"},
                        Case{"check " + script_user.string(), "s.xml:1: script: file 'fifo.lua' is not a regular "
                                                              "file (a pipe)"},
                        Case{"check " + mechanism_user.string() + " --allow-read /dev",
                             "m.xml:2: mechanism: file '/dev/zero' is not a regular file (a device)"}}) {
    const auto start = std::chrono::steady_clock::now();
    const auto run = RunMechflow(c.args);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(run.exit_code, 2) << c.args;
    EXPECT_THAT(run.err, HasSubstr(c.expected)) << c.args;
    EXPECT_LT(seconds, 2.0) << c.args;
  }
}

// A diagram folder d/ beside a folder secret/ it must not read, with a file of
// every kind a diagram names in both.
class DiagramReadsTest : public HostileDiagramTest {
 protected:
  DiagramReadsTest() {
    fs::create_directories(dir_ / "d" / "sub");
    fs::create_directories(dir_ / "secret");
    for (const fs::path& folder : {dir_ / "d", dir_ / "secret"}) {
      std::ofstream(folder / "t.csv") << "0 1\n1 2\n";
      std::ofstream(folder / "t2.csv") << "x\\y, 0, 1\n0, 1, 2\n1, 3, 4\n";
      std::ofstream(folder / "l.lua") << "function outputs(t) return t end\n";
      std::ofstream(folder / "s.lua") << "-- a control script\n";
      std::ofstream(folder / "m.xml") << "<mechanism name=\"m\"><body name=\"B\" mass=\"1\" inertia=\"1 1 1\"/>"
                                          "<joint name=\"j\" type=\"translational\" body1=\"Base0\" body2=\"B\" "
                                          "axis=\"0 0 1\"/></mechanism>\n";
    }
  }
  // A diagram in d/ whose line 2 names `file` the way `kind` does; returns its path.
  std::string Naming(const std::string& kind, const std::string& file) {
    std::string element;
    if (kind == "table" || kind == "motion_table")
      element = "<blocks><block type=\"" + kind + "\" name=\"b\" file=\"" + file + "\"/></blocks>";
    else if (kind == "lookup" || kind == "lookup_2d")  // inputs connected
      element = "<blocks><block type=\"clock\" name=\"c\"/><block type=\"" + kind + "\" name=\"b\" file=\"" +
                file + "\"/></blocks><connections>" +
                (kind == "lookup" ? "<connect from=\"c.y\" to=\"b.u\"/>"
                                  : "<connect from=\"c.y\" to=\"b.u1\"/><connect from=\"c.y\" to=\"b.u2\"/>") +
                "</connections>";
    else if (kind == "lua")
      element = "<blocks><block type=\"lua\" name=\"b\" src=\"" + file + "\" outputs=\"y\"/></blocks>";
    else if (kind == "script")
      element = "<script src=\"" + file + "\"/>";
    else
      element = "<mechanism name=\"m\" src=\"" + file + "\"/>";
    const fs::path path = dir_ / "d" / ("uses_" + kind + ".xml");
    std::ofstream(path) << "<diagram>\n" << element << "\n<solver t_end=\"1\"/></diagram>\n";
    return path.string();
  }
};

TEST_F(DiagramReadsTest, FilesADiagramNamesStayInItsFolderTree) {
  fs::create_symlink(dir_ / "secret" / "t.csv", dir_ / "d" / "link.csv");
  fs::create_directory_symlink(dir_ / "secret", dir_ / "d" / "sub" / "folder_link");
  const std::string secret = (dir_ / "secret").string();
  for (const std::string kind : {"table", "lookup", "lookup_2d", "motion_table", "lua", "script", "mechanism"}) {
    const std::string file = kind == "lookup_2d" ? "t2.csv" : kind == "lua" ? "l.lua" : kind == "script" ? "s.lua"
                             : kind == "mechanism"                          ? "m.xml"
                                                                            : "t.csv";
    // inside: plain, and through a folder that is a link inside the tree
    const auto inside = RunMechflow("check " + Naming(kind, file));
    EXPECT_EQ(inside.exit_code, 0) << kind << ": " << inside.err;
    // every kind by a relative path; the other ways out (cheap tests) for tables
    std::vector<std::string> ways_out = {"../secret/" + file};
    if (kind == "table")
      ways_out.insert(ways_out.end(), {secret + "/t.csv", "sub/folder_link/t.csv", "sub/../../secret/t.csv"});
    for (const std::string& outside : ways_out) {
      const auto run = RunMechflow("check " + Naming(kind, outside));
      EXPECT_EQ(run.exit_code, 2) << kind << " " << outside;
      EXPECT_THAT(run.err, HasSubstr("uses_" + kind + ".xml:2: ")) << kind << " " << outside;
      EXPECT_THAT(run.err, HasSubstr("lies outside the diagram's folder")) << kind << " " << outside;
      EXPECT_THAT(run.err, HasSubstr("--allow-read DIR")) << kind << " " << outside;
      // the user may allow the folder
      const auto allowed = RunMechflow("check " + Naming(kind, outside) + " --allow-read " + secret);
      EXPECT_EQ(allowed.exit_code, 0) << kind << " " << outside << ": " << allowed.err;
    }
  }
  // a link inside the tree that points out is the file it points to
  const auto link = RunMechflow("check " + Naming("table", "link.csv"));
  EXPECT_EQ(link.exit_code, 2);
  EXPECT_THAT(link.err, HasSubstr("uses_table.xml:2: block 'b' parameter 'file': file 'link.csv' lies outside"));
  // a file that is not there is still "not found"
  EXPECT_THAT(RunMechflow("check " + Naming("table", "missing.csv")).err, HasSubstr("file 'missing.csv' not found"));
}

TEST_F(DiagramReadsTest, EveryCommandThatLoadsADiagramTakesAllowRead) {
  const std::string diagram = Naming("table", "../secret/t.csv") + " --allow-read " + (dir_ / "secret").string();
  EXPECT_EQ(RunMechflow("run " + diagram + " --out " + Out()).exit_code, 0);
  for (const std::string command : {"graph", "modes", "sweep --vary x=1,2", "force-analysis --element e"}) {
    const auto run = RunMechflow(command + " " + diagram + " --out " + Out());
    EXPECT_THAT(run.err, ::testing::Not(HasSubstr("--allow-read"))) << command;
    EXPECT_THAT(run.err, ::testing::Not(HasSubstr("lies outside"))) << command;
  }
  // psd reads a results file the user names, not a diagram
  EXPECT_THAT(RunMechflow("psd r.csv --signal x --allow-read " + dir_.string()).err,
              HasSubstr("unknown option '--allow-read'"));
  const auto missing = RunMechflow("check " + Naming("table", "t.csv") + " --allow-read " + (dir_ / "none").string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("--allow-read '" + (dir_ / "none").string() + "': no such folder"));
}

// What a message quotes of a line it could not read: a short excerpt, every
// control character and byte that is not UTF-8 written \xNN, whatever the
// line's length.
TEST_F(DiagramReadsTest, MessagesQuoteAShortEscapedExcerpt) {
  const std::string hostile = "\x1b]0;owned\x07\x1b[2J\xff" + std::string(4 << 20, 'x');
  std::ofstream(dir_ / "d" / "bad.csv", std::ios::binary) << "0 1\n1 2\n" << hostile << "\n";
  const auto table = RunMechflow("check " + Naming("table", "bad.csv"));
  EXPECT_EQ(table.exit_code, 2);
  EXPECT_THAT(table.err,
              HasSubstr("bad.csv:3: expected two numbers (t, y), found '\\x1B]0;owned\\x07\\x1B[2J\\xFFxxx"));
  // an expression (XML lets no control character through), and a Lua error
  const fs::path expression = dir_ / "d" / "e.xml";
  std::ofstream(expression) << "<diagram><identifiers><identifier name=\"k\" value=\"(1 + "
                            << std::string(256 << 10, 'y') << " +\"/></identifiers></diagram>\n";
  const auto identifier = RunMechflow("check " + expression.string());
  EXPECT_EQ(identifier.exit_code, 2);
  EXPECT_THAT(identifier.err, HasSubstr("'(1 + yyy"));
  const fs::path lua = dir_ / "d" / "l.xml";
  std::ofstream(lua) << "<diagram><script>error(string.char(27) .. '[2J' .. string.rep('z', 1000000))</script>"
                        "</diagram>\n";
  const auto script = RunMechflow("check " + lua.string());
  EXPECT_EQ(script.exit_code, 2);
  EXPECT_THAT(script.err, HasSubstr("\\x1B[2Jzzz"));
  for (const auto* run : {&table, &identifier, &script}) {
    EXPECT_LT(run->err.size(), 3000u) << run->err.substr(0, 200);
    EXPECT_EQ(run->err.find('\x1b'), std::string::npos);
    EXPECT_EQ(run->err.find('\xff'), std::string::npos);
    EXPECT_THAT(run->err, HasSubstr("..."));
  }
}

// Spreadsheet programs start a CSV file with a UTF-8 byte-order mark: the
// first point is a point, not a header.
TEST_F(DiagramReadsTest, AByteOrderMarkIsNotText) {
  std::ofstream(dir_ / "d" / "t.csv", std::ios::binary) << "\xEF\xBB\xBF" "0, 5\n1, 7\n2, 9\n";
  const fs::path path = dir_ / "d" / "bom.xml";
  std::ofstream(path) << "<diagram name=\"bom\"><identifiers><identifier name=\"k\" value=\"1\"/></identifiers>\n"
                         "<blocks><block type=\"table\" name=\"t\" file=\"t.csv\"/>\n"
                         "<block type=\"gain\" name=\"g\" k=\"k\"/></blocks>\n"
                         "<connections><connect from=\"t.y\" to=\"g.u\"/></connections>\n"
                         "<solver t_end=\"1\"/><output interval=\"0.5\"><log signal=\"g.y\" label=\"y\"/></output>\n"
                         "</diagram>\n";
  std::ofstream(dir_ / "d" / "set.txt", std::ios::binary) << "\xEF\xBB\xBF" "k = 2\n";
  const auto run = RunMechflow("run " + path.string() + " --set-file " + (dir_ / "d" / "set.txt").string() +
                               " --quiet --out " + Out());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // y = k t(t): 2 * 5 at t = 0, 2 * 6 at 0.5
  EXPECT_EQ(ReadFile(dir_ / "out" / "bom.csv"), "time,y\n0,10\n0.5,12\n1,14\n");
}

// Reads the quoted strings of DOT as Graphviz does (\" a quote, a backslash
// pair kept, nothing else special) and checks that each ends; returns the
// strings as read.
std::vector<std::string> DotStrings(const std::string& dot) {
  std::vector<std::string> strings;
  for (std::size_t i = 0; i < dot.size(); ++i) {
    if (dot[i] != '"') continue;
    std::string s;
    for (++i;; ++i) {
      if (i >= dot.size()) {
        ADD_FAILURE() << "a string that never ends: " << s;
        return strings;
      }
      if (dot[i] == '"') break;
      if (dot[i] == '\\' && i + 1 < dot.size() && (dot[i + 1] == '"' || dot[i + 1] == '\\')) {
        s += dot[i + 1] == '"' ? "\"" : "\\\\";
        ++i;
      } else {
        EXPECT_FALSE(dot[i] == '\\' && i + 1 < dot.size() && dot[i + 1] == '\n') << "a line continued in " << s;
        s += dot[i];
      }
    }
    strings.push_back(s);
  }
  return strings;
}

// In a record label, what Graphviz shows of one field: \X is X for the
// characters that structure a record, \\ a backslash.
std::string RecordShown(const std::string& field) {
  std::string out;
  for (std::size_t i = 0; i < field.size(); ++i) {
    if (field[i] == '\\' && i + 1 < field.size()) ++i;
    else EXPECT_EQ(std::string("{}|<>").find(field[i]), std::string::npos) << "unescaped in " << field;
    out += field[i];
  }
  return out;
}

TEST_F(HostileDiagramTest, GraphEscapesEveryName) {
  const fs::path path = dir_ / "x.xml";
  std::ofstream(path) << "<diagram name=\"x\\\"><output csv=\"r.csv\"/><blocks>\n"
                         "<block type=\"constant\" name=\"a&quot;b&lt;c&gt;{d}|e f\\\" value=\"1\"/>\n"
                         "<block type=\"gain\" name=\"g\\\" k=\"2\"/></blocks>\n"
                         "<connections><connect from=\"a&quot;b&lt;c&gt;{d}|e f\\.y\" to=\"g\\.u\"/></connections>\n"
                         "</diagram>\n";
  const auto run = RunMechflow("graph " + path.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::vector<std::string> strings = DotStrings(run.out);
  ASSERT_EQ(strings.size(), 5u) << run.out;  // the graph's name, two fonts, two labels
  EXPECT_EQ(strings[0], "x\\\\");
  // a label's fields: {ports}|name\n(type)|{ports}, the constant's without inputs
  const std::size_t type = strings[3].find("\\n(constant)|");
  ASSERT_NE(type, std::string::npos) << strings[3];
  EXPECT_EQ(RecordShown(strings[3].substr(1, type - 1)), "a\"b<c>{d}|e f\\");
  EXPECT_THAT(strings[4], HasSubstr("|g\\\\\\n(gain)|"));
  if (std::system("command -v dot >/dev/null 2>&1") == 0) {
    std::ofstream(dir_ / "g.dot") << run.out;
    EXPECT_EQ(std::system(("dot -Tsvg " + (dir_ / "g.dot").string() + " >/dev/null").c_str()), 0);
  }
}

// A <shape>'s curve is evaluated when the diagram is loaded: a point it
// cannot give is bad input at its line, not a failed run.
TEST_F(HostileDiagramTest, AnInfiniteCurveIsBadInput) {
  const fs::path path = dir_ / "c.xml";
  std::ofstream(path) << "<diagram><mechanism name=\"m\">\n"
                         "<body name=\"B\" mass=\"1\" inertia=\"1 1 1\"/>\n"
                         "<joint name=\"j\" type=\"translational\" body1=\"Base0\" body2=\"B\" axis=\"0 0 1\"/>\n"
                         "<shape type=\"curve\" x=\"1/u\" y=\"0\" z=\"0\" u=\"0 1\" samples=\"4\"/>\n"
                         "</mechanism><solver t_end=\"0.1\"/></diagram>\n";
  for (const std::string command : {"check ", "run "}) {
    const auto run = RunMechflow(command + path.string() + " --out " + Out() + (command == "run " ? " --animate" : ""));
    EXPECT_EQ(run.exit_code, 2) << command << run.err;
    EXPECT_THAT(run.err, HasSubstr("c.xml:4: ")) << command;
  }
  // so is a prescribed motion that is not finite where the mechanism is assembled, at the start
  std::ofstream(path) << "<diagram><mechanism name=\"m\">\n"
                         "<body name=\"B\" mass=\"1\" inertia=\"1 1 1\"/>\n"
                         "<joint name=\"j\" type=\"generalized\" body1=\"Base0\" body2=\"B\">\n"
                         "<et type=\"rt\" axis=\"1 0 0\" value=\"1/t\"/><et type=\"tv\" axis=\"0 0 1\"/>\n"
                         "</joint></mechanism><solver t_end=\"0.1\"/></diagram>\n";
  const auto check = RunMechflow("check " + path.string());
  EXPECT_EQ(check.exit_code, 2) << check.err;
  EXPECT_THAT(check.err, HasSubstr("c.xml:4: joint 'j' transformation 1: time function '1/t' is not finite at t = 0"));
}

// Everything mechflow starts (gnuplot) from here on: the command line runs
// `cat INPUT | [PATH=...] mechflow ARGS` in the test's folder, so that what a
// child reads from its standard input would be INPUT.
class ChildProcessTest : public HostileDiagramTest {
 protected:
  ChildProcessTest() { std::ofstream(dir_ / "input") << "system \"touch " << Marker() << "\"\n"; }
  std::string Marker() const { return (dir_ / kMarker).string(); }
  mechflow::testing::CommandOutcome RunPiped(const std::string& args, const std::string& path_first = "") {
    const std::string command = "cd " + dir_.string() + " && cat input | " +
                                (path_first.empty() ? "" : "PATH=" + path_first + ":$PATH ") + MECHFLOW_BINARY + " " +
                                args + " >" + (dir_ / "stdout").string() + " 2>" + (dir_ / "stderr").string();
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ReadFile(dir_ / "stdout"), ReadFile(dir_ / "stderr")};
  }
  // A fake gnuplot first on PATH running `body` (sh); returns the folder to put first.
  std::string FakeGnuplot(const std::string& body) {
    fs::create_directories(dir_ / "bin");
    const fs::path fake = dir_ / "bin" / "gnuplot";
    std::ofstream(fake) << "#!/bin/sh\n" << body << "\n";
    fs::permissions(fake, fs::perms::owner_all);
    return (dir_ / "bin").string();
  }
};

// A name beginning with '-' was gnuplot's option and gnuplot read commands
// from mechflow's input; '<' and '|' open a command in gnuplot, '+' is its
// pseudo-file. On every route a file name takes to gnuplot: refused, bad
// input, and nothing piped in runs.
TEST_F(ChildProcessTest, NoNameReachesGnuplotAsAnOptionOrACommand) {
  const std::string sweep_diagram = (dir_ / "s.xml").string();
  std::ofstream(sweep_diagram) << "<diagram name=\"s\">\n<identifiers><identifier name=\"k\" value=\"1\"/></identifiers>\n"
                                  "<blocks><block type=\"constant\" name=\"c\" value=\"k\"/></blocks>\n<solver t_end=\"1\"/>\n"
                                  "<output interval=\"0.5\" csv=\"-r.csv\"><log signal=\"c.y\"/></output>\n</diagram>\n";
  const std::string spectrum_diagram = (dir_ / "p.xml").string();
  std::ofstream(spectrum_diagram) << "<diagram name=\"-x\">\n<blocks><block type=\"sine\" name=\"s\"/></blocks>\n"
                                     "<solver t_end=\"1\"/>\n<output interval=\"0.01\">\n<log signal=\"s.y\"/>"
                                     "<spectrum signal=\"s.y\"/></output>\n</diagram>\n";
  std::ofstream results(dir_ / "-x.csv");
  results << "time,x\n";
  for (int i = 0; i < 64; ++i) results << i * 0.01 << "," << (i % 4) << "\n";
  results.close();
  struct Route {
    std::string args, refusal;
  };
  // Diagram() writes d.xml; each route keeps its own copy
  const auto named = [&](const std::string& file, const std::string& output) {
    fs::rename(Diagram("d", output), dir_ / file);
    return "run " + (dir_ / file).string() + " --out out";
  };
  for (const Route& r :
       {Route{named("d1.xml", "plot=\"-x.png\""), "d1.xml:4: plot file '-x.png' may not begin with '-', '+', '<' or"},
        // gnuplot runs what follows '|' in `set output` and '<' in `plot` (in the output folder)
        Route{named("d2.xml", "plot=\"|touch made.png\""), "d2.xml:4: plot file '|touch made.png' may not begin"},
        Route{named("d3.xml", "csv=\"&lt;touch made.csv\" plot=\"x.png\""), "csv file '<touch made.csv' may not"},
        Route{named("d4.xml", "csv=\"+\" plot=\"x.png\""), "d4.xml:4: csv file '+' may not begin with"},
        Route{"run " + spectrum_diagram + " --out out", "file '-x.csv' named after the diagram may not begin with"},
        Route{"sweep " + sweep_diagram + " --vary k=1,2 --out out", "s.xml:5: csv file '-r.csv' may not begin"},
        Route{"psd -x.csv --signal x --out out", "-x.psd.csv': the name begins with '-', which gnuplot would take"}}) {
    const auto run = RunPiped(r.args);
    EXPECT_EQ(run.exit_code, 2) << r.args << "\n" << run.err;
    EXPECT_THAT(run.err, HasSubstr(r.refusal)) << r.args;
    EXPECT_FALSE(fs::exists(Marker())) << r.args;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "made.png")) << r.args;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "made.csv")) << r.args;
    fs::remove(Marker());
  }
}

// Whatever the names, gnuplot reads nothing from mechflow's standard input
// and its script's name cannot be an option.
TEST_F(ChildProcessTest, GnuplotReadsNoInputAndItsScriptIsNotAnOption) {
  const std::string bin = FakeGnuplot("printf '%s' \"$1\" >" + (dir_ / "argument").string() + "\ncat >" +
                                      (dir_ / "read").string());
  const auto run = RunPiped("run " + Diagram("d", "plot=\"d.png\"") + " --out out", bin);
  EXPECT_EQ(run.exit_code, 1);  // the fake draws nothing
  EXPECT_THAT(run.err, HasSubstr("gnuplot made no"));
  EXPECT_EQ(ReadFile(dir_ / "argument"), "./d.png.gp");
  EXPECT_TRUE(fs::exists(dir_ / "read"));
  EXPECT_EQ(ReadFile(dir_ / "read"), "");
}

// gnuplot exits 0 having written a plot a full disk cut short: the plot is
// named as cut and removed, the command fails, the other files stay.
TEST_F(ChildProcessTest, AnIncompletePlotIsNamedAsCutAndRemoved) {
  // the plot's name from the script's `set output` line; a PNG's signature and
  // header without the rest, an SVG without its closing tag
  const std::string bin = FakeGnuplot(
      "out=$(sed -n \"s/^set output '\\(.*\\)'$/\\1/p\" \"$1\")\n"
      "case \"$out\" in *.svg) printf '<?xml version=\"1.0\"?>\\n<svg>\\n<g>' >\"$out\" ;;\n"
      "*) printf '\\211PNG\\r\\n\\032\\n\\0\\0\\0\\rIHDR' >\"$out\" ;; esac");
  for (const std::string plot : {"d.png", "d.svg"}) {
    const auto run = RunPiped("run " + Diagram("d", "plot=\"" + plot + "\"") + " --out out", bin);
    EXPECT_EQ(run.exit_code, 1) << plot << run.err;
    EXPECT_THAT(run.err, HasSubstr("gnuplot's plot '" + (dir_ / "out" / plot).string() + "' is cut: it has no ")) << plot;
    EXPECT_THAT(run.err, HasSubstr("; not written " + plot)) << plot;
    EXPECT_THAT(run.out, ::testing::Not(HasSubstr("wrote " + (dir_ / "out" / plot).string()))) << plot;
    EXPECT_FALSE(fs::exists(dir_ / "out" / plot)) << plot;
    EXPECT_TRUE(fs::exists(dir_ / "out" / "d.csv")) << plot;
  }
  // gnuplot's own, whole plots pass the same check
  const auto real = RunPiped("run " + Diagram("d", "plot=\"d.png\"") + " --out out");
  EXPECT_EQ(real.exit_code, 0) << real.err;
}

// A disk that fills during the run (a file size limit, which fails writes as
// a full disk does): the results CSV is kept with its rows before the cut and
// named as cut, gnuplot's plot of it is not claimed, the command fails.
TEST_F(ChildProcessTest, AFullDiskCutsTheResultsWhichAreNamedAsCut) {
  const fs::path path = dir_ / "long.xml";
  std::ofstream(path) << "<diagram name=\"long\">\n<blocks><block type=\"sine\" name=\"s\"/></blocks>\n"
                         "<solver t_end=\"2\"/>\n<output interval=\"0.0005\" plot=\"long.png\">"
                         "<log signal=\"s.y\"/></output>\n</diagram>\n";
  const auto run = RunPiped("run " + path.string() + " --out out", "");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::uintmax_t whole = fs::file_size(dir_ / "out" / "long.csv");  // about 70 KiB
  // files of at most 16 KiB for mechflow and gnuplot (inherited), and EFBIG
  // instead of SIGXFSZ
  struct rlimit old {};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = old;
  small.rlim_cur = 16384;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string command = "cd " + dir_.string() + " && " + MECHFLOW_BINARY + " run " + path.string() +
                              " --out out >stdout 2>stderr </dev/null";
  const int status = std::system(command.c_str());
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  const std::string out = ReadFile(dir_ / "stdout"), err = ReadFile(dir_ / "stderr");
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 1) << err;
  const std::string csv = (dir_ / "out" / "long.csv").string();
  EXPECT_THAT(err, HasSubstr("error writing '" + csv + "' after "));
  EXPECT_THAT(err, HasSubstr("File too large; the file is cut there, its rows before are kept"));
  EXPECT_THAT(err, HasSubstr("; cut long.csv (File too large: its rows before the cut are kept)"));
  EXPECT_THAT(out, ::testing::Not(HasSubstr("wrote " + csv)));
  EXPECT_LT(fs::file_size(csv), whole);
  EXPECT_EQ(fs::file_size(csv), 16384u);  // kept, up to the cut
  // gnuplot's plot of it: cut by the same limit (gnuplot exits 0), never claimed
  EXPECT_THAT(err, HasSubstr("long.png' is cut: it has no PNG end (IEND chunk) (is the disk full?); the incomplete "
                             "file is removed"));
  EXPECT_THAT(out, ::testing::Not(HasSubstr("long.png")));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "long.png"));
}

// A file written whole (HTML, glTF, units, report, spectra, scripts) that a
// full disk cuts is removed, and the error says so.
TEST_F(HostileDiagramTest, AFileWrittenWholeIsRemovedWhenCut) {
  struct rlimit old {};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of the signal
  struct rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const OutputFolder folder(Out());
  std::string error;
  try {
    folder.Write("d.html", std::string(1 << 16, 'x'));
  } catch (const WriteError& e) {
    error = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_THAT(error, HasSubstr("d.html' after 4096 of 65536 bytes: File too large; the incomplete file is removed"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "d.html"));
}

}  // namespace
}  // namespace mechflow::cli
