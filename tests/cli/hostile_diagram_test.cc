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

#include "blocks/results.h"
#include "cli/output_folder.h"
#include "cli/results_file.h"
#include "cli/plot.h"
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
                        Case{"check " + block_user.string(), "b.xml:2: block 'l' (lua): Lua file '" + fifo.string() +
                                                                 "' is not a regular file (a pipe)"},
                        Case{"check " + table_user.string(), "t.xml:2: block 't' (table): table file '/dev/zero' is not "
                                                             "a regular file (a device)"},
                        Case{"check " + dir_.string(), "is not a regular file (a folder)"},
                        Case{"check " + fifo.string(), "is not a regular file (a pipe)"},
                        Case{"check " + big.string(), "has 67108875 bytes; input files may have at most 64 MiB"},
                        Case{"check " + script_user.string(), "s.xml:1: script file '" + fifo.string() +
                                                                  "' is not a regular file (a pipe)"},
                        Case{"check " + mechanism_user.string(), "m.xml:2: mechanism file '/dev/zero' is not a "
                                                                 "regular file (a device)"}}) {
    const auto start = std::chrono::steady_clock::now();
    const auto run = RunMechflow(c.args);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(run.exit_code, 2) << c.args;
    EXPECT_THAT(run.err, HasSubstr(c.expected)) << c.args;
    EXPECT_LT(seconds, 2.0) << c.args;
  }
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
