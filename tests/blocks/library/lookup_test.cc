// Lookup tables of signals (blocks/library/interpolation.h, lookup.h):
// interpolation and extrapolation against polynomials they must reproduce
// exactly, events at corners only, and the refusals.

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "blocks/library/interpolation.h"
#include "blocks/library/lookup.h"
#include "mech/errors.h"
#include "tests/blocks/block_test_util.h"
#include "tests/test_util.h"

namespace mechflow::blocks {
namespace {

using ::testing::HasSubstr;

double Cubic(double x) { return 0.5 * x * x * x - 2 * x * x + x - 3; }
double CubicSlope(double x) { return 1.5 * x * x - 4 * x + 1; }
double CubicCurvature(double x) { return 3 * x - 4; }

TEST(InterpolationTest, TheNotAKnotSplineReproducesACubicExactly) {
  // uneven breakpoints: the spline of a cubic's values is that cubic
  const std::vector<double> x = {-1, -0.3, 0.5, 0.6, 1.7, 2.0, 3.5};
  std::vector<double> y;
  for (const double v : x) y.push_back(Cubic(v));
  for (const Extrapolation e : {Extrapolation::kHold, Extrapolation::kLinear}) {
    const Axis axis(x, Interpolation::kCubic, e, "t");
    const Curve curve(axis, y);
    for (double u = -1; u <= 3.5; u += 0.01) {
      const CurvePoint p = curve.At(axis, u, axis.Segment(u));
      EXPECT_NEAR(p.value, Cubic(u), 1e-12) << u;
      EXPECT_NEAR(p.slope, CubicSlope(u), 1e-11) << u;
      EXPECT_NEAR(p.curvature, CubicCurvature(u), 1e-10) << u;
    }
    // beyond the ends: the end value (hold) or the end tangent (linear)
    const CurvePoint below = curve.At(axis, -2, axis.Segment(-2));
    if (e == Extrapolation::kHold) {
      EXPECT_NEAR(below.value, Cubic(-1), 1e-12);
      EXPECT_EQ(below.slope, 0.0);
    } else {
      EXPECT_NEAR(below.value, Cubic(-1) - CubicSlope(-1), 1e-11);
      EXPECT_NEAR(below.slope, CubicSlope(-1), 1e-11);
    }
  }
}

TEST(InterpolationTest, ThreePointsGiveTheParabolaAndTwoTheLine) {
  const Axis three({0, 1, 3}, Interpolation::kCubic, Extrapolation::kHold, "t");
  const Curve parabola(three, {1, 2, 10});  // 1 + 0 x + x^2
  EXPECT_NEAR(parabola.At(three, 2, three.Segment(2)).value, 5, 1e-14);
  EXPECT_NEAR(parabola.At(three, 2, three.Segment(2)).curvature, 2, 1e-14);
  const Axis two({0, 2}, Interpolation::kCubic, Extrapolation::kHold, "t");
  const Curve line(two, {1, 5});
  EXPECT_NEAR(line.At(two, 0.5, two.Segment(0.5)).value, 2, 1e-15);
  EXPECT_EQ(line.At(two, 0.5, two.Segment(0.5)).curvature, 0);
}

TEST(InterpolationTest, LinearAndStepPieces) {
  const Axis linear({0, 1, 3}, Interpolation::kLinear, Extrapolation::kLinear, "t");
  const Curve ramp(linear, {0, 2, 3});
  EXPECT_DOUBLE_EQ(ramp.At(linear, 0.25, linear.Segment(0.25)).value, 0.5);
  EXPECT_DOUBLE_EQ(ramp.At(linear, 2, linear.Segment(2)).value, 2.5);
  EXPECT_DOUBLE_EQ(ramp.At(linear, 5, linear.Segment(5)).value, 4);    // the last slope, 0.5, continued
  EXPECT_DOUBLE_EQ(ramp.At(linear, -1, linear.Segment(-1)).value, -2);  // the first, 2
  const Axis step({0, 1, 3}, Interpolation::kStep, Extrapolation::kHold, "t");
  const Curve stairs(step, {0, 2, 3});
  EXPECT_EQ(stairs.At(step, 0.99, step.Segment(0.99)).value, 0);
  EXPECT_EQ(stairs.At(step, 1, step.Segment(1)).value, 2);
  EXPECT_EQ(stairs.At(step, 7, step.Segment(7)).value, 3);
}

TEST(InterpolationTest, CornersAreWhereTheCurveIsNotSmooth) {
  auto corners = [](Interpolation i, Extrapolation e) {
    return Axis({0, 1, 2, 3}, i, e, "t").num_regions() - 1;
  };
  EXPECT_EQ(corners(Interpolation::kLinear, Extrapolation::kHold), 4);    // kinks inside and at the ends
  EXPECT_EQ(corners(Interpolation::kLinear, Extrapolation::kLinear), 2);  // the ends continue straight
  EXPECT_EQ(corners(Interpolation::kStep, Extrapolation::kHold), 4);
  EXPECT_EQ(corners(Interpolation::kCubic, Extrapolation::kHold), 2);     // only the ends
  EXPECT_EQ(corners(Interpolation::kCubic, Extrapolation::kLinear), 2);   // y'' jumps at the ends
  EXPECT_EQ(corners(Interpolation::kCubic, Extrapolation::kError), 2);
}

TEST(InterpolationTest, RefusalsNameTheTable) {
  EXPECT_THAT(mechflow::testing::InputErrorOf([] { Axis({0, 1, 1}, Interpolation::kLinear, Extrapolation::kHold, "T"); }),
              HasSubstr("T: breakpoints must increase strictly, but 1 follows 1"));
  EXPECT_THAT(mechflow::testing::InputErrorOf([] { Axis({0}, Interpolation::kLinear, Extrapolation::kHold, "T"); }),
              HasSubstr("at least two breakpoints"));
  EXPECT_THAT(mechflow::testing::InputErrorOf([] { Axis({0, 1}, Interpolation::kStep, Extrapolation::kLinear, "T"); }),
              HasSubstr("a step table has no slope to extrapolate"));
  EXPECT_THAT(mechflow::testing::InputErrorOf([] { ParseInterpolation("spline"); }), HasSubstr("step, linear or cubic"));
  EXPECT_THAT(mechflow::testing::InputErrorOf([] { ParseExtrapolation("clamp"); }), HasSubstr("hold, linear or error"));
}

// y = lookup(u) with u = t (a clock) over [0, 3.5]
mechflow::testing::XmlRun RunLookup(const std::string& attributes, double t_end = 3.5) {
  return mechflow::testing::RunXml("<diagram><blocks><block type='clock' name='u'/><block type='lookup' name='f' " +
                         attributes +
                         "/></blocks><connections><connect from='u.y' to='f.u'/></connections>"
                         "<solver t_end='" +
                         std::to_string(t_end) + "' rtol='1e-10' atol='1e-12'/><output interval='0.01'>"
                         "<log signal='f.y'/></output></diagram>");
}

TEST(LookupBlockTest, LinearTablesSwitchPiecesAtEveryBreakpointTheInputCrosses) {
  const auto run = RunLookup("points='0 0; 1 2; 2 2.5; 3 0' interpolation='linear'");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  // corners 1, 2, 3 crossed (t = 0 starts on the first)
  EXPECT_EQ(run.sim->stats().events, 3);
  const auto t = run.Column("time"), y = run.Column("f.y");
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double v = t[i];
    const double exact = v < 1 ? 2 * v : v < 2 ? 2 + 0.5 * (v - 1) : v < 3 ? 2.5 - 2.5 * (v - 2) : 0;
    EXPECT_NEAR(y[i], exact, 1e-12) << v;
  }
}

TEST(LookupBlockTest, CubicTablesHaveNoEventsInside) {
  std::string points;
  for (const double x : {-1.0, 0.5, 1.0, 2.2, 4.0})
    points += (points.empty() ? "" : "; ") + blocks::testing::Num(x) + " " + blocks::testing::Num(Cubic(x));
  const auto run = RunLookup("points='" + points + "' interpolation='cubic'");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_EQ(run.sim->stats().events, 0);
  const auto t = run.Column("time"), y = run.Column("f.y");
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(y[i], Cubic(t[i]), 1e-12) << t[i];
}

TEST(LookupBlockTest, ErrorExtrapolationEndsTheRunWhereTheInputLeavesTheTable) {
  const auto run = RunLookup("points='0 0; 2 1' extrapolation='error'");
  EXPECT_FALSE(run.outcome.ok);
  EXPECT_THAT(run.outcome.failure, HasSubstr("lookup 'f': input 2"));
  EXPECT_THAT(run.outcome.failure, HasSubstr("lies outside the table [0, 2] and extrapolation is \"error\""));
  EXPECT_NEAR(run.outcome.t_reached, 2.0, 1e-9);
  // the rows up to there are kept
  EXPECT_NEAR(run.Column("time").back(), 2.0, 1e-9);
}

TEST(LookupBlockTest, ATableOfAMechanismCoordinateDrivesItsForce) {
  // a nonlinear spring written two ways: the mechanism's own tabulated law,
  // and a lookup of the coordinate feeding a joint force input
  const std::string table = "0 0; 0.1 -50; 0.2 -200; 0.3 -450";
  const auto mech = [&](const std::string& force, const std::string& blocks, const std::string& connections) {
    return mechflow::testing::RunXml(
        "<diagram><identifiers><identifier name='F' value='0'/></identifiers><mechanism name='m' gravity='0 0 0'>" +
        std::string(blocks.empty() ? "" : "<input name='F'/>") + "<body name='B' mass='1' inertia='1 1 1'/>"
        "<joint name='j' type='translational' body1='Base0' body2='B' axis='1 0 0' q0='0.25'/>" +
        force + "<sensor name='x' kind='coordinate' dof='j'/></mechanism><blocks>" + blocks +
        "</blocks><connections>" + connections +
        "</connections><solver t_end='2' rtol='1e-10' atol='1e-12'/><output interval='0.01'><log signal='m.x'/>"
        "</output></diagram>");
  };
  const auto own = mech("<joint_force name='s' dof='j' type='points' points='" + table +
                            "' interpolation='linear' extrapolation='linear'/>",
                        "", "");
  const auto looked = mech("<joint_force name='s' dof='j' type='expression' expression='F'/>",
                           "<block type='lookup' name='law' points='" + table +
                               "' interpolation='linear' extrapolation='linear'/>",
                           "<connect from='m.x' to='law.u'/><connect from='law.y' to='m.F'/>");
  ASSERT_TRUE(own.outcome.ok) << own.outcome.failure;
  ASSERT_TRUE(looked.outcome.ok) << looked.outcome.failure;
  const auto a = own.Column("m.x"), b = looked.Column("m.x");
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-7);
  // it oscillates through the corners at 0.1 and 0.2: events
  EXPECT_GT(looked.sim->stats().events, 4);
}

double Bicubic(double x, double y) { return x * x * x - 2 * x * y * y + y * y * y + 1; }

TEST(Lookup2DBlockTest, CubicReproducesABicubicAndLinearIsBilinear) {
  const std::vector<double> xs = {0, 0.5, 1.5, 2, 3}, ys = {-1, 0, 0.7, 2};
  std::vector<std::vector<double>> values;
  for (const double x : xs) {
    values.emplace_back();
    for (const double y : ys) values.back().push_back(Bicubic(x, y));
  }
  std::string rows;  // shortest round-trip texts: the table holds these values exactly
  for (std::size_t i = 0; i < xs.size(); ++i) {
    for (std::size_t j = 0; j < ys.size(); ++j) rows += blocks::testing::Num(values[i][j]) + " ";
    rows += i + 1 < xs.size() ? "; " : "";
  }
  // along two paths through the table: u1 = t, u2 = 2 - t and u2 = t - 1
  for (const std::string interpolation : {"cubic", "linear"})
    for (const double sign : {-1.0, 1.0}) {
      const auto run = mechflow::testing::RunXml(
          "<diagram><blocks><block type='clock' name='u1'/><block type='ramp' name='u2' slope='" +
          blocks::testing::Num(sign) + "' initial='" + (sign < 0 ? "2" : "-1") + "'/>"
          "<block type='lookup_2d' name='f' x='0 0.5 1.5 2 3' y='-1 0 0.7 2' values='" + rows +
          "' interpolation='" + interpolation +
          "'/></blocks><connections><connect from='u1.y' to='f.u1'/><connect from='u2.y' to='f.u2'/>"
          "</connections><solver t_end='3' rtol='1e-10' atol='1e-12'/><output interval='0.01'>"
          "<log signal='f.y'/></output></diagram>");
      ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
      const auto t = run.Column("time"), f = run.Column("f.y");
      for (std::size_t k = 0; k < t.size(); ++k) {
        const double x = t[k], y = sign < 0 ? 2 - t[k] : t[k] - 1;
        if (interpolation == "cubic") {
          EXPECT_NEAR(f[k], Bicubic(x, y), 1e-12) << x << ", " << y;
          continue;
        }
        // bilinear: the cell's corner values weighted by the position in it
        const int i = std::min<int>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin() - 1, xs.size() - 2);
        const int j = std::min<int>(std::upper_bound(ys.begin(), ys.end(), y) - ys.begin() - 1, ys.size() - 2);
        const double a = (x - xs[i]) / (xs[i + 1] - xs[i]), b = (y - ys[j]) / (ys[j + 1] - ys[j]);
        const double exact = (1 - a) * (1 - b) * values[i][j] + a * (1 - b) * values[i + 1][j] +
                             (1 - a) * b * values[i][j + 1] + a * b * values[i + 1][j + 1];
        EXPECT_NEAR(f[k], exact, 1e-12) << x << ", " << y;
      }
    }
}

TEST(Lookup2DBlockTest, ReadsAFileWithItsCornerLabel) {
  const std::string path = ::testing::TempDir() + "mechflow_lookup_2d.csv";
  std::ofstream(path) << "# friction coefficient over speed (rows) and temperature (columns)\n"
                         "v\\T, 20, 80\n0, 0.5, 0.4\n1, 0.3, 0.2\n";
  std::vector<double> x, y;
  std::vector<std::vector<double>> values;
  ReadTable2DCsv(ReadInputFile(path, "table file"), path, &x, &y, &values);
  EXPECT_EQ(x, (std::vector<double>{0, 1}));
  EXPECT_EQ(y, (std::vector<double>{20, 80}));
  EXPECT_EQ(values, (std::vector<std::vector<double>>{{0.5, 0.4}, {0.3, 0.2}}));
  std::ofstream(path) << "v\\T, 20, 80\n0, 0.5, 0.4\n1, 0.3\n";
  EXPECT_THAT(mechflow::testing::InputErrorOf(
                  [&] { ReadTable2DCsv(ReadInputFile(path, "table file"), path, &x, &y, &values); }),
              HasSubstr(path + ":3: expected 3 numbers (x_i and one value per column), found 2"));
  std::ofstream(path) << "0, 0.5, 0.4\n1, 0.3, 0.1\n";
  EXPECT_THAT(mechflow::testing::InputErrorOf(
                  [&] { ReadTable2DCsv(ReadInputFile(path, "table file"), path, &x, &y, &values); }),
              HasSubstr("starts with a line of the column breakpoints"));
}

}  // namespace
}  // namespace mechflow::blocks
