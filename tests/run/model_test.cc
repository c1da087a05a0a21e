// run::Model: one load, many runs, each the same as a fresh load would give.

#include "run/model.h"

#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "blocks/outputs/csv.h"
#include "diagrams/xml_reader.h"
#include "mech/errors.h"
#include "run/sinks.h"
#include "tests/cli/mechflow_command.h"

namespace mechflow {
namespace {

using ::testing::HasSubstr;

std::string Example(const std::string& name) { return std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + name; }

// Short runs: the tests compare numbers, not long stretches of them.
run::RunOptions Short(double t_end) {
  run::RunOptions o;
  o.t_end = t_end;
  return o;
}

std::vector<std::vector<double>> Rows(run::Model& model, const run::RunOptions& options) {
  run::MemorySink sink;
  const run::RunResult r = model.Run(options, &sink);
  EXPECT_EQ(r.status, run::Status::kOk) << r.reason;
  return sink.columns();
}

// The control script changes an identifier (sim:set torque) and the
// controller keeps its last output: a second run on the same built diagram
// would start from what the first left; the model rebuilds, so it does not.
TEST(RunModel, SecondRunIsTheFirstAgain) {
  run::Model model(Example("pendulum_pd_control.xml"));
  const auto first = Rows(model, Short(2.5));
  const auto second = Rows(model, Short(2.5));
  ASSERT_GT(first.front().size(), 100u);
  EXPECT_EQ(first, second);
}

// A script that keeps a count of its runs in a local of its chunk, and sets
// an identifier from it: a second run on the diagram the first ran would see
// count 2; rebuilt from the description, it sees 1 again.
TEST(RunModel, SecondRunForgetsWhatTheScriptKept) {
  const std::string xml = R"(<diagram name="count">
  <identifiers><identifier name="gain" value="0"/></identifiers>
  <blocks>
    <block type="identifier" name="g" identifier="gain"/>
    <block type="integrator" name="x" initial="0"/>
  </blocks>
  <connections><connect from="g.y" to="x.u"/></connections>
  <script>
    local runs = 0
    function init(sim) runs = runs + 1; sim:set("gain", runs) end
  </script>
  <solver t_end="1"/>
  <output interval="0.5"><log signal="x.y"/></output>
</diagram>)";
  run::Model model(diagrams::ReadDiagramText(xml, "count.xml"));
  const auto first = Rows(model, {});
  ASSERT_EQ(first.size(), 2u);
  EXPECT_NEAR(first[1].back(), 1.0, 1e-12);  // gain 1 for 1 s
  EXPECT_EQ(Rows(model, {}), first);
}

// A diagram without Lua at run time is run again on its built diagram; its
// friction block's stick/slip modes and the integrators' states start afresh,
// so the rows equal the first run's and a fresh load's, bit for bit.
TEST(RunModel, ARunAgainOnTheBuiltDiagramIsTheFirstAgain) {
  run::Model model(Example("stick_slip_blocks.xml"));
  const auto first = Rows(model, Short(2.0));
  const auto second = Rows(model, Short(2.0));
  run::Model fresh(Example("stick_slip_blocks.xml"));
  ASSERT_GT(first.front().size(), 1000u);
  EXPECT_EQ(first, second);
  EXPECT_EQ(Rows(fresh, Short(2.0)), first);
}

TEST(RunModel, SetThenRunIsALoadWithSet) {
  run::Model model(Example("damping_ratio.xml"));
  const auto before = Rows(model, Short(1));
  model.Set("Beta", 0.3);  // any case, as --set
  const auto after = Rows(model, Short(1));
  diagrams::LoadOptions with_set;
  with_set.overrides = {{"beta", 0.3}};
  run::Model loaded_so(Example("damping_ratio.xml"), with_set);
  EXPECT_EQ(after, Rows(loaded_so, Short(1)));
  EXPECT_NE(after, before);  // the value took effect
  // a second Set of the same name replaces the first
  model.Set("beta", 0.1);
  EXPECT_EQ(Rows(model, Short(1)), before);
}

// SetOptions replaces every setting at once, Set's included; a build made
// with the same settings serves on (no rebuild), another is rebuilt.
TEST(RunModel, SetOptionsIsAModelMadeWithThem) {
  run::Model model(Example("damping_ratio.xml"));
  const auto before = Rows(model, Short(1));
  diagrams::LoadOptions with_set;
  with_set.overrides = {{"beta", 0.3}};
  model.SetOptions(with_set);
  run::Model loaded_so(Example("damping_ratio.xml"), with_set);
  EXPECT_EQ(Rows(model, Short(1)), Rows(loaded_so, Short(1)));
  const diagrams::LoadedDiagram* built = &model.Loaded();
  model.Set("beta", 0.3);  // what it is already
  model.SetOptions(model.options());
  EXPECT_EQ(&model.Loaded(), built);
  model.SetOptions({});  // Set's value goes too
  EXPECT_NE(&model.Loaded(), built);
  EXPECT_EQ(Rows(model, Short(1)), before);
}

TEST(RunModel, MemoryColumnsAreTheCsvFile) {
  const std::string path = ::testing::TempDir() + "run_model_test_" + std::to_string(getpid()) + ".csv";
  run::Model model(Example("damping_ratio.xml"));
  std::vector<std::string> names;
  {
    run::CsvFileSink file(path, {"time", "position", "force"});  // header as given
    const run::RunResult r = model.Run(Short(1), &file);
    EXPECT_EQ(file.Close(), "");
    EXPECT_EQ(file.rows(), r.rows);
    for (const run::Column& c : r.columns) names.push_back(c.name);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"time", "m.z", "m.force"}));
  const auto columns = Rows(model, Short(1));
  std::string text = blocks::CsvHeader({"time", "position", "force"});
  std::vector<double> row(columns.size());
  for (std::size_t r = 0; r < columns.front().size(); ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c) row[c] = columns[c][r];
    blocks::AppendCsvRow(row.data(), static_cast<int>(row.size()), &text);
  }
  EXPECT_EQ(testing::ReadFile(path), text);
  std::filesystem::remove(path);
}

TEST(RunModel, RunWithoutSinkGivesOutcomeAndFigures) {
  run::Model model(Example("damping_ratio.xml"));
  const run::RunResult r = model.Run(Short(1), nullptr);
  EXPECT_EQ(r.status, run::Status::kOk);
  EXPECT_DOUBLE_EQ(r.t_reached, 1.0);
  EXPECT_EQ(r.rows, 201);  // 0 .. 1 s every 0.005 s
  EXPECT_GT(r.stats.steps, 0);
  ASSERT_EQ(r.columns.size(), 3u);
  EXPECT_EQ(r.columns[0].unit, "s");
  EXPECT_EQ(r.columns[1].unit, "m");
}

TEST(RunModel, InterruptAndProgress) {
  run::Model model(Example("damping_ratio.xml"));
  run::RunOptions o = Short(1);
  int calls = 0;
  o.progress = [&](double) { ++calls; };
  EXPECT_EQ(model.Run(o).rows, calls);  // after every row
  volatile std::sig_atomic_t flag = SIGINT;  // as a handler leaves it
  o.interrupt = &flag;
  const run::RunResult r = model.Run(o);
  EXPECT_EQ(r.status, run::Status::kInterrupted);
  EXPECT_EQ(r.signal, SIGINT);
  EXPECT_LT(r.t_reached, 1.0);
}

TEST(RunModel, LogsTheSignalsAsked) {
  run::Model model(Example("damping_ratio.xml"));
  run::RunOptions o = Short(0.5);
  o.log = std::vector<std::string>{"m.force"};
  run::MemorySink rows;
  const run::RunResult r = model.Run(o, &rows);
  ASSERT_EQ(r.columns.size(), 2u);
  EXPECT_EQ(r.columns[1].name, "m.force");
  EXPECT_EQ(rows.columns().size(), 2u);
  o.log = std::vector<std::string>{"m.forse"};
  EXPECT_THROW(model.Run(o), InputError);
}

TEST(RunModel, RefusesWhatItCannotDo) {
  run::Model model(Example("damping_ratio.xml"));
  try {
    model.Set("betta", 0.2);
    FAIL() << "an unknown name was taken";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no identifier named 'betta' (did you mean 'beta'?)"));
  }
  try {
    model.Set("cdiss", 1.0);
    FAIL() << "a derived identifier was set";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("set the identifiers it depends on instead"));
  }
  // a refused value leaves the model as it was
  model.Set("mass", -1.0);
  EXPECT_THROW(model.Run(Short(0.1)), InputError);
  model.Set("mass", 1000.0);
  EXPECT_EQ(model.Run(Short(0.1)).status, run::Status::kOk);
}

// x' = cos(t) with a sampled hold of sin(t) (period 0.1) beside it: rows
// at irregular instants, between steps, on a sample hit and at t_end, are
// exactly those instants and hold sin(t) to the tolerance; the hold shows the
// value of the last hit before each instant.
TEST(RunModel, RowsAtExactlyTheGivenTimes) {
  const std::string xml = R"(<diagram name="sine">
  <blocks>
    <block type="sine" name="c" amplitude="1" frequency="0.15915494309189535" phase="1.5707963267948966"/>
    <block type="integrator" name="x" initial="0"/>
    <block type="sine" name="s" amplitude="1" frequency="0.15915494309189535"/>
    <block type="sample_hold" name="h" period="0.1"/>
  </blocks>
  <connections><connect from="c.y" to="x.u"/><connect from="s.y" to="h.u"/></connections>
  <solver t_end="2" rtol="1e-10" atol="1e-12"/>
  <output interval="0.5"><log signal="x.y"/><log signal="h.y"/></output>
</diagram>)";
  run::Model model(diagrams::ReadDiagramText(xml, "sine.xml"));
  run::RunOptions o;
  o.times = {0.0137, 0.3, 0.30000001, 0.7, 1.2345678, 2.0};
  const auto rows = Rows(model, o);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0], o.times);
  for (std::size_t i = 0; i < o.times.size(); ++i) {
    const double t = o.times[i];
    EXPECT_NEAR(rows[1][i], std::sin(t), 1e-8) << t;
    EXPECT_NEAR(rows[2][i], std::sin(std::floor(t / 0.1 + 1e-9) * 0.1), 1e-12) << t;
  }
  // no row at t_start unless asked; a later t_end runs on without rows
  o.times = {0.5};
  o.t_end = 3.0;
  run::MemorySink one;
  const run::RunResult r = model.Run(o, &one);
  EXPECT_EQ(r.t_reached, 3.0);
  ASSERT_EQ(one.rows(), 1);
  EXPECT_NEAR(one.columns()[1][0], std::sin(0.5), 1e-8);
}

TEST(RunModel, RefusesOutputTimesItCannotKeep) {
  run::Model model(Example("damping_ratio.xml"));
  const auto refusal = [&](std::vector<double> times, std::optional<double> interval = {}) {
    run::RunOptions o = Short(1.0);
    o.times = std::move(times);
    o.interval = interval;
    try {
      model.Run(o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_THAT(refusal({0.2, 0.1}), HasSubstr("the output time 0.1 s (number 2 in the list) is not after the one before (0.2 s)"));
  EXPECT_THAT(refusal({0.2, 0.2}), HasSubstr("the times must increase"));
  EXPECT_THAT(refusal({0.5, 1.5}), HasSubstr("the output time 1.5 s (number 2 in the list) is after t_end = 1 s: run to t_end = 1.5 s"));
  EXPECT_THAT(refusal({-0.1}), HasSubstr("is before t_start = 0 s"));
  EXPECT_THAT(refusal({0.1, std::nan("")}), HasSubstr("the output time nan s (number 2 in the list) is not a finite number"));
  EXPECT_THAT(refusal({0.1}, 0.01), HasSubstr("output at given times and an output interval exclude each other"));
}

// A control timer (every 0.01 s) between output times (every 0.02 s): rows
// on the output grid only, not at each timer.
TEST(RunModel, TimersBetweenOutputTimesAddNoRows) {
  run::Model model(Example("pendulum_pd_control.xml"));
  run::RunOptions o = Short(1.0);
  o.interval = 0.02;
  const auto rows = Rows(model, o);
  ASSERT_EQ(rows[0].size(), 51u);
  for (std::size_t k = 0; k < rows[0].size(); ++k) EXPECT_NEAR(rows[0][k], 0.02 * k, 1e-15) << k;
}

// The file is read with the folders the options give: --allow-read for a
// mechanism's src= outside the diagram's folder, --library for a subsystem
// file found there only.
TEST(RunModel, ReadsWithTheFoldersOfItsOptions) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / ("run_model_folders_" + std::to_string(getpid()));
  fs::create_directories(dir / "d");
  fs::create_directories(dir / "other");
  fs::create_directories(dir / "lib");
  std::ofstream(dir / "other" / "m.xml") << "<mechanism name=\"m\"><body name=\"B\" mass=\"1\" inertia=\"1 1 1\"/>"
                                            "<joint name=\"j\" type=\"translational\" body1=\"Base0\" body2=\"B\" "
                                            "axis=\"0 0 1\"/></mechanism>\n";
  std::ofstream(dir / "d" / "mech.xml") << "<diagram><mechanism name=\"m\" src=\"../other/m.xml\"/>"
                                           "<solver t_end=\"0.1\"/></diagram>\n";
  std::ofstream(dir / "lib" / "sub.xml") << "<subsystem name=\"sub\"><output name=\"y\"/></subsystem>\n";
  std::ofstream(dir / "d" / "top.xml") << "<diagram><blocks><block type=\"subsystem\" name=\"s\" src=\"sub.xml\"/>"
                                          "</blocks></diagram>\n";

  run::LoadOptions allow;
  allow.allow_read = {(dir / "other").string()};
  EXPECT_EQ(run::Model((dir / "d" / "mech.xml").string(), allow).Loaded().diagram->num_states(), 2);
  const auto error = [&](const std::vector<std::string>& library) {
    run::LoadOptions options;
    options.library = library;
    try {
      run::Model((dir / "d" / "top.xml").string(), options);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(loaded)");
  };
  EXPECT_THAT(error({}), HasSubstr("file 'sub.xml' not found"));
  // found: whatever the loader then says of it, the file is not missing
  EXPECT_THAT(error({(dir / "lib").string()}), ::testing::Not(HasSubstr("not found")));
}

}  // namespace
}  // namespace mechflow
