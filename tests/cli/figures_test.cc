// What `mechflow run` prints and writes for <report>s (the figures and the
// .report.csv beside the results) and for warning events (a contact deeper
// than its max_penetration: once per element, with the time).

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "blocks/solver/simulator.h"
#include "cli/commands.h"
#include "cli/report.h"
#include "tests/test_util.h"

namespace mechflow::cli::figures_test {  // names of its own: the files of its folder are compiled together
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

std::string ReadFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// x'' = -x from x = 0, x' = 1 (x = sin t): the peak is 1 at pi/2.
const char* kSine =
    "<diagram name='sine'>\n"
    "<blocks><block type='integrator' name='v' initial='1'/><block type='integrator' name='x'/>\n"
    "<block type='gain' name='minus' k='-1'/></blocks>\n"
    "<connections><connect from='v.y' to='x.u'/><connect from='x.y' to='minus.u'/>"
    "<connect from='minus.y' to='v.u'/></connections>\n"
    "<solver t_end='4' rtol='1e-10' atol='1e-12'/>\n"
    "<output interval='0.5'><log signal='x.y'/>\n"
    "<report peak='x.y' label='largest x' unit='m'/>\n"
    "<report min='v.y'/>\n"
    "<report crossing='x.y' level='0.5'/>\n"
    "<report crossing='x.y' level='0.5' unit='ms' label='half way'/>\n"
    "</output></diagram>\n";

TEST(FiguresTest, RunPrintsTheFiguresAndWritesThemBesideTheResults) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("figures_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "sine.xml") << kSine;
  std::ostringstream out, err;
  ASSERT_EQ(Main({"run", (dir / "sine.xml").string(), "--out", (dir / "results").string()}, out, err), 0)
      << err.str();
  // sin t peaks at 1 at pi/2 = 1.5708; v = cos t is lowest, -1, at pi
  EXPECT_THAT(out.str(), HasSubstr("largest x: 1 m at t = 1.5708 s\n"));
  EXPECT_THAT(out.str(), HasSubstr("min of v.y: -1 at t = 3.14159 s\n"));
  // a crossing's time in its unit: s unless the report names another
  EXPECT_THAT(out.str(), HasSubstr("crossing of x.y: reached at t = 0.5235987"));
  EXPECT_THAT(out.str(), HasSubstr("half way: reached at t = 523.59877"));  // ms: pi/6 s is 523.599 ms
  const std::string csv = ReadFile(dir / "results" / "sine.report.csv");
  std::istringstream lines(csv);
  std::string header, first, second, third;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  std::getline(lines, third);
  EXPECT_EQ(header, "label,kind,signal,value,unit,time");
  EXPECT_THAT(first, ::testing::StartsWith("largest x,peak,x.y,"));
  // full precision: the value and time parse back to the closed form
  double value = 0, time = 0;
  ASSERT_EQ(std::sscanf(first.c_str(), "largest x,peak,x.y,%lf,m,%lf", &value, &time), 2) << first;
  EXPECT_NEAR(value, 1.0, 1e-9);
  EXPECT_NEAR(time, M_PI / 2, 1e-5);
  EXPECT_THAT(second, ::testing::StartsWith("min of v.y,min,v.y,"));
  // no unit asked: a time's is s (an integrator's own output has none to give)
  ASSERT_EQ(std::sscanf(third.c_str(), "crossing of x.y,crossing,x.y,%lf,s,%lf", &value, &time), 2) << third;
  EXPECT_NEAR(value, M_PI / 6, 1e-5);  // sin t = 0.5
}

TEST(FiguresTest, AFailedRunMarksItsFigures) {
  std::ostringstream out;
  blocks::ReportFigure f;
  f.label = "peak";
  f.unit = "N";
  f.found = true;
  f.value = 12.5;
  f.time = 0.25;
  PrintFigures({f}, false, out);
  EXPECT_EQ(out.str(), "peak: 12.5 N at t = 0.25 s (up to the failure)\n");
}

// A ball at 1 m/s onto a soft, undamped contact (gravity off): penetration
// sin(w t) v0 / w with w = 10 1/s reaches 0.1 m; the bound 0.05 m is passed at
// t = asin(0.5) / w after touching at t = 0.01 s.
std::string SoftLanding(const std::string& bound) {
  return "<diagram>\n<mechanism name='m' gravity='0 0 0'>\n"
         "<body name='Ball' mass='1' inertia='0.1 0.1 0.1'/>\n"
         "<joint name='z' type='translational' body1='Base0' body2='Ball' axis='0 0 1' q0='0.01' v0='-1'/>\n"
         "<contact name='floor' type='points_plane' body1='Ball' points='0 0 0' body2='Base0' normal='0 0 1'\n"
         "         stiffness='100'" + bound + "/>\n"
         "<sensor name='z' kind='coordinate' dof='z'/>\n"
         "</mechanism>\n<solver t_end='0.5' rtol='1e-10' atol='1e-12'/>\n"
         "<output interval='0.01'><log signal='m.z'/></output>\n</diagram>\n";
}

TEST(FiguresTest, PenetrationBeyondTheBoundWarnsOnceWithTheTime) {
  const auto run = testing::RunXml(SoftLanding(" max_penetration='0.05'"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  // the bound is an event of its own: touch, bound, leave
  ASSERT_EQ(run.sim->events().size(), 3u);
  const double t_bound = 0.01 + std::asin(0.5) / 10;
  EXPECT_NEAR(run.sim->events()[1].time, t_bound, 1e-8);
  // once per element, even when the events repeat
  auto events = run.sim->events();
  events.push_back(events[1]);
  std::ostringstream out;
  PrintEventWarnings(*run.loaded.diagram, events, out);
  EXPECT_EQ(out.str(), "warning: t = 0.0623599 s: test.xml:5: m.floor: penetration exceeds max_penetration = 0.05 m "
                       "(is the contact too soft, or is a body passing through the plane?)\n");
  // the landing itself is unchanged by the bound's event: it leaves at 1 m/s
  // after half a period, pi / w
  const auto z = run.Column("m.z");
  EXPECT_NEAR(z.back(), 0.5 - (0.01 + M_PI / 10), 1e-6);
}

TEST(FiguresTest, NoWarningWithinTheBoundAndTheDefaultIsFiveCentimetres) {
  const auto within = testing::RunXml(SoftLanding(" max_penetration='0.2'"));
  ASSERT_TRUE(within.outcome.ok) << within.outcome.failure;
  EXPECT_EQ(within.sim->events().size(), 2u);
  std::ostringstream out;
  PrintEventWarnings(*within.loaded.diagram, within.sim->events(), out);
  EXPECT_EQ(out.str(), "");
  const auto by_default = testing::RunXml(SoftLanding(""));
  std::ostringstream warned;
  PrintEventWarnings(*by_default.loaded.diagram, by_default.sim->events(), warned);
  EXPECT_THAT(warned.str(), HasSubstr("max_penetration = 0.05 m"));
}

}  // namespace
}  // namespace mechflow::cli::figures_test
