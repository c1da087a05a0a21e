// Friction elements with memory driven by an imposed harmonic displacement
// (the force-analysis runs of docs/ELEMENTS.md 3.10): EF-2, the Jenkins
// loop of the elastic-friction element with d = 0, and EF2-4, the dynamic
// stiffness and phase of the elastic-friction-2 element under its three
// friction limits; plus the mode invariants and bad input of elastic-friction-2.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace mechflow {
namespace {

using testing::InputErrorOf;
using testing::LoadXml;
using testing::RunXml;
using testing::XmlRun;

constexpr int kSamplesPerPeriod = 4000;
constexpr int kPeriods = 3;

// Body P is driven along x as 1 + a sin(2 pi f t) from Base0's origin, so the
// element `e` between them has x' = x - 1 = a sin(2 pi f t).
std::string ImposedMotion(const std::string& element, double a, double f) {
  const auto number = [](double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);
    return std::string(text);
  };
  const double period = 1.0 / f;
  return R"xml(<diagram name="imposed">
  <identifiers><identifier name="a" value=")xml" + number(a) + R"xml("/>
    <identifier name="f" value=")xml" + number(f) + R"xml("/></identifiers>
  <mechanism name="m" gravity="0 0 0">
    <body name="P" mass="1" inertia="1 1 1"/>
    <joint name="jP" type="generalized" body1="Base0" body2="P">
      <et type="tt" axis="1 0 0" value="1 + a*sin(2*pi*f*t)"/>
    </joint>
    )xml" + element + R"xml(
    <sensor name="force" kind="element" element="e"/>
    <sensor name="x" kind="element" element="e" quantity="length"/>
    <sensor name="mode" kind="element" element="e" quantity="mode"/>
    <sensor name="deflection" kind="element" element="e" quantity="deflection"/>
  </mechanism>
  <solver t_end=")xml" + number(kPeriods * period) + R"xml(" rtol="1e-10" atol="1e-12"/>
  <output interval=")xml" + number(period / kSamplesPerPeriod) + R"xml(">
    <log signal="m.force"/><log signal="m.x"/><log signal="m.mode"/><log signal="m.deflection"/>
  </output>
</diagram>)xml";
}

// First harmonic of the reaction R = -F (the force that imposes the motion)
// over the last period, the exact loop area (the work done on the element)
// and the force amplitude, all by the trapezoid rule over the logged rows
// (the output grid plus a row at each event).
struct Harmonic {
  double stiffness, phase_deg, loop_area, force_amplitude;
};

Harmonic Analyse(const XmlRun& run, double a, double f) {
  const auto t = run.Column("time"), force = run.Column("m.force"), x = run.Column("m.x");
  const double w = 2 * M_PI * f, from = t.back() - 1 / f - 1e-9;
  double rs = 0, rc = 0, area = 0, peak = 0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (t[i - 1] < from) continue;
    const double r0 = -force[i - 1], r1 = -force[i], dt = t[i] - t[i - 1];
    rs += f * dt * (r0 * std::sin(w * t[i - 1]) + r1 * std::sin(w * t[i]));  // (2/T) * trapezoid
    rc += f * dt * (r0 * std::cos(w * t[i - 1]) + r1 * std::cos(w * t[i]));
    area += 0.5 * (r0 + r1) * (x[i] - x[i - 1]);
    peak = std::max(peak, std::abs(force[i]));
  }
  return {std::hypot(rs, rc) / a, std::atan2(rc, rs) * 180 / M_PI, area, peak};
}

std::string ElasticFriction2(double mu, const std::string& limit = "transmitted", const std::string& extra = "") {
  return R"xml(<force name="e" type="elastic_friction2" body1="Base0" body2="P" c1="400" c2="100" l0="1" mu=")xml" +
         std::to_string(mu) + R"xml(" limit=")xml" + limit + "\" " + extra + "/>";
}

// EF-2: d = 0, k_s = 1. The loop is a parallelogram: plateaus +-F while
// sliding, slope c while stuck; the work per cycle is 4 F (a - F/c).
TEST(FrictionHysteresisTest, JenkinsParallelogramEF2) {
  const double F = 10, c = 1e4, a = 0.01, f = 1;
  const XmlRun run = RunXml(ImposedMotion(R"xml(<force name="e" type="elastic_friction" body1="Base0" body2="P"
      friction="10" ratio="1" c="10000" d="0"/>)xml", a, f));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto force = run.Column("m.force"), x = run.Column("m.x"), mode = run.Column("m.mode");
  int stuck = 0, sliding = 0;
  for (std::size_t i = 1; i < force.size(); ++i) {
    ASSERT_LE(std::abs(force[i]), F * (1 + 1e-9));
    if (mode[i] != 0) {
      ++sliding;
      ASSERT_NEAR(force[i], -mode[i] * F, 1e-9 * F);
    } else if (mode[i - 1] == 0 && std::abs(x[i] - x[i - 1]) > 1e-9) {
      ++stuck;  // slope c between two samples in the same stick phase (the deflection is integrated)
      ASSERT_NEAR(-(force[i] - force[i - 1]) / (x[i] - x[i - 1]), c, 1e-4 * c);
    }
  }
  // Stuck while x' moves 2F/c from a turning point: arccos(1 - 2F/(c a))
  // of each pi, about 20.5 % of the time.
  const double stick_fraction = std::acos(1 - 2 * F / (c * a)) / M_PI;
  EXPECT_NEAR(static_cast<double>(stuck) / (stuck + sliding), stick_fraction, 2e-3);
  const Harmonic h = Analyse(run, a, f);
  const double dissipated = 4 * F * (a - F / c);  // 0.36 J
  EXPECT_NEAR(h.loop_area, dissipated, 1e-5 * dissipated);
  // For a harmonic displacement the first harmonic carries all the work.
  EXPECT_NEAR(M_PI * a * a * h.stiffness * std::sin(h.phase_deg * M_PI / 180), dissipated, 1e-5 * dissipated);
}

// d = 0 with k_s > 1: the link holds up to k_s F, then the reset drops the
// deflection to F/c as sliding begins (the force jumps from k_s F to F).
TEST(FrictionHysteresisTest, JenkinsResetsTheDeflectionWhenItBreaksAway) {
  const double F = 10, c = 1e4, a = 0.01;
  const XmlRun run = RunXml(ImposedMotion(R"xml(<force name="e" type="elastic_friction" body1="Base0" body2="P"
      friction="10" ratio="1.5" c="10000" d="0"/>)xml", a, 1));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto force = run.Column("m.force"), delta = run.Column("m.deflection"), mode = run.Column("m.mode");
  double peak = 0;
  int breaks = 0;
  for (std::size_t i = 1; i < force.size(); ++i) {
    peak = std::max(peak, std::abs(force[i]));
    if (mode[i] != 0) {
      ASSERT_NEAR(delta[i], mode[i] * F / c, 1e-12);
    }
    if (mode[i - 1] == 0 && mode[i] != 0) ++breaks;
  }
  EXPECT_GE(breaks, 4);
  EXPECT_LE(peak, 1.5 * F * (1 + 1e-6));
  EXPECT_GE(peak, 1.5 * F * 0.99);  // sampled just before the break
  // Each stick spans s = (k_s + 1) F/c from a turning point with the mean
  // force -(k_s - 1) F/2 against the motion, so the work per cycle is
  // 2 F (2a - s) + (k_s - 1) F s = 4 F a - (3 - k_s)(k_s + 1) F^2/c = 0.3625 J.
  // (The trapezoid rule straddles two force jumps a cycle: ~1.4e-4 relative.)
  const double ks = 1.5, work = 4 * F * a - (3 - ks) * (ks + 1) * F * F / c;
  EXPECT_NEAR(Analyse(run, a, 1).loop_area, work, 3e-4 * work);
}

// EF2-4: K and phase from the first harmonic, against the table of 3.8
// (printed to 0.01 N/m and 0.01 deg); the default law's are independent of
// amplitude and frequency.
TEST(FrictionHysteresisTest, DynamicStiffnessOfElasticFriction2EF2_4) {
  const double mus[5] = {0, 0.1, 0.2, 0.3, 0.5};
  const double k_default[5] = {80.00, 82.14, 86.83, 93.95, 117.58};
  const double phase_default[5] = {0, 2.75, 5.09, 6.97, 9.23};
  const double k_spring[5] = {80.00, 81.48, 84.04, 87.17, 94.37};
  for (int i = 0; i < 5; ++i) {
    const XmlRun run = RunXml(ImposedMotion(ElasticFriction2(mus[i]), 1e-3, 1));
    ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
    const Harmonic h = Analyse(run, 1e-3, 1);
    EXPECT_NEAR(h.stiffness, k_default[i], 6e-3) << "mu " << mus[i];
    EXPECT_NEAR(h.phase_deg, phase_default[i], 6e-3) << "mu " << mus[i];
    EXPECT_NEAR(h.loop_area, M_PI * 1e-6 * h.stiffness * std::sin(h.phase_deg * M_PI / 180), 1e-4 * h.loop_area + 1e-15);
    const XmlRun b = RunXml(ImposedMotion(ElasticFriction2(mus[i], "spring"), 1e-3, 1));
    ASSERT_TRUE(b.outcome.ok) << b.outcome.failure;
    EXPECT_NEAR(Analyse(b, 1e-3, 1).stiffness, k_spring[i], 6e-3) << "law (b), mu " << mus[i];
  }
  // amplitude and frequency independence of the default law (mu = 0.2)
  for (const auto& [a, f] : {std::pair{2e-3, 1.0}, std::pair{3e-3, 1.0}, std::pair{1e-3, 5.0}}) {
    const XmlRun run = RunXml(ImposedMotion(ElasticFriction2(0.2), a, f));
    ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
    const Harmonic h = Analyse(run, a, f);
    EXPECT_NEAR(h.stiffness, 86.83, 6e-3) << a << " m at " << f << " Hz";
    EXPECT_NEAR(h.phase_deg, 5.09, 6e-3) << a << " m at " << f << " Hz";
  }
}

// EF2-4, law (c): a constant limit mu F_N = 0.2 N makes K depend on the
// amplitude (260.7, 161.7, 128.2 N/m at 1, 2, 3 mm), not on the frequency.
TEST(FrictionHysteresisTest, ConstantLimitStiffnessDependsOnAmplitudeEF2_4c) {
  const double amplitudes[3] = {1e-3, 2e-3, 3e-3}, k[3] = {260.7, 161.7, 128.2};
  for (int i = 0; i < 3; ++i)
    for (double f : {1.0, 3.0}) {
      const XmlRun run = RunXml(ImposedMotion(ElasticFriction2(0.2, "constant", R"xml(normal_force="1")xml"), amplitudes[i], f));
      ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
      EXPECT_NEAR(Analyse(run, amplitudes[i], f).stiffness, k[i], 0.06) << amplitudes[i] << " m at " << f << " Hz";
    }
}

// At every sample: stuck, the slider force stays within mu0 N and x2 is
// held; sliding, it equals s mu N. With mu0 > mu, x2 jumps when it breaks.
TEST(FrictionHysteresisTest, ElasticFriction2ModesKeepTheirInvariantsUnderEveryLimit) {
  const double c1 = 400, c2 = 100, mu = 0.1, mu0 = 0.3, fn = 1;
  for (const std::string limit : {"transmitted", "spring", "constant"}) {
    const XmlRun run = RunXml(ImposedMotion(
        ElasticFriction2(mu, limit, limit == "constant" ? R"xml(mu0="0.3" normal_force="1")xml" : R"xml(mu0="0.3")xml"),
        4e-3, 1));
    ASSERT_TRUE(run.outcome.ok) << limit << ": " << run.outcome.failure;
    const auto force = run.Column("m.force"), x2 = run.Column("m.deflection"), mode = run.Column("m.mode");
    int jumps = 0;
    for (std::size_t i = 1; i < force.size(); ++i) {
      const double tension = -force[i], slider = tension - c2 * x2[i];
      const double n = limit == "transmitted" ? std::abs(tension) : limit == "spring" ? std::abs(c2 * x2[i]) : fn;
      if (mode[i] == 0) {
        ASSERT_LE(std::abs(slider), mu0 * n * (1 + 1e-6) + 1e-9) << limit << " sample " << i;
        if (mode[i - 1] == 0) {
          ASSERT_EQ(x2[i], x2[i - 1]) << limit << " sample " << i;
        }
      } else {
        ASSERT_NEAR(slider, mode[i] * mu * n, 1e-9) << limit << " sample " << i;
        if (mode[i - 1] == 0) {
          ++jumps;
          EXPECT_GT(std::abs(x2[i] - x2[i - 1]), 1e-5) << limit << ": x2 jumps when the slider breaks away";
        }
      }
    }
    EXPECT_GE(jumps, 4) << limit;
  }
  (void)c1;
}

TEST(FrictionHysteresisTest, BadElasticFriction2InputNamesTheLine) {
  auto error = [](const std::string& attributes) {
    return InputErrorOf([&] {
      LoadXml(R"xml(<diagram name="d">
  <mechanism name="m">
    <body name="P" mass="1" inertia="1 1 1"/>
    <joint name="j" type="translational" body1="Base0" body2="P" point1="1 0 0" axis="1 0 0"/>
    <force name="e" type="elastic_friction2" body1="Base0" body2="P" )xml" + attributes + R"xml(/>
  </mechanism>
</diagram>)xml");
    });
  };
  EXPECT_EQ(error(R"xml(c1="400" c2="100" mu="0.2")xml"), "");
  EXPECT_NE(error(R"xml(c1="-400" c2="100" mu="0.2")xml").find("test.xml:5"), std::string::npos);
  EXPECT_NE(error(R"xml(c1="-400" c2="100" mu="0.2")xml").find("c1 must be positive"), std::string::npos);
  EXPECT_NE(error(R"xml(c1="400" c2="-1" mu="0.2")xml").find("c2 must not be negative"), std::string::npos);
  EXPECT_NE(error(R"xml(c1="400" c2="100" mu="-0.2")xml").find("test.xml:5"), std::string::npos);
  EXPECT_NE(error(R"xml(c1="400" c2="100" mu="-0.2")xml").find("mu must not be negative"), std::string::npos);
  EXPECT_NE(error(R"xml(c1="400" c2="100" mu="0.3" mu0="0.2")xml").find("mu0 must not be below"), std::string::npos);
  EXPECT_NE(error(R"xml(c1="400" c2="100" mu="1.2")xml").find("below 1"), std::string::npos);
  EXPECT_NE(error(R"xml(c1="400" c2="100" mu="0.2" limit="springy")xml").find("did you mean 'spring'"), std::string::npos);
  EXPECT_NE(error(R"xml(c1="400" c2="100" mu="0.2" limit="constant")xml").find("needs normal_force"), std::string::npos);
  EXPECT_NE(error(R"xml(c1="400" c2="100" mu="0.2" limit="constant" normal_force="-1")xml").find("must not be negative"),
            std::string::npos);
  // the elastic-friction element: d = 0 needs c
  EXPECT_NE(InputErrorOf([] {
              LoadXml(R"xml(<diagram name="d">
  <mechanism name="m">
    <body name="P" mass="1" inertia="1 1 1"/>
    <joint name="j" type="translational" body1="Base0" body2="P" point1="1 0 0" axis="1 0 0"/>
    <force name="e" type="elastic_friction" body1="Base0" body2="P" friction="10" c="0" d="0"/>
  </mechanism>
</diagram>)xml");
            }).find("test.xml:5"),
            std::string::npos);
}

}  // namespace
}  // namespace mechflow
