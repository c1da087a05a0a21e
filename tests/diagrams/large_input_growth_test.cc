// Loading grows linearly with the diagram: N identifiers (numbers, or each
// an expression of the one above) and a line of N bodies on translational
// joints load at 10 N in well under the time and memory a quadratic step
// would take (100 times). Two measures: the bytes asked of malloc while
// loading (exact and repeatable: a dense N x N matrix or an environment of
// all identifiers per expression shows at once) and the CPU time, the
// fastest of three (a linear search per name allocates nothing).

#include <algorithm>
#include <ctime>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_util.h"
// last: it declares the malloc family without the C library's exception specifiers
#include "tests/malloc_counter.h"

namespace mechflow::diagrams {
namespace {

using Generator = std::function<std::string(int)>;

std::string Identifiers(int n, bool chained) {
  std::string xml = "<diagram name='ids'><identifiers>\n<identifier name='p0' value='1'/>\n";
  for (int i = 1; i < n; ++i)
    xml += "<identifier name='p" + std::to_string(i) + "' value='" +
           (chained ? "P" + std::to_string(i - 1) + " + 1" : std::to_string(i)) + "'/>\n";
  // a block parameter and an identifier block read the last one
  const std::string last = "p" + std::to_string(n - 1);
  return xml + "</identifiers><blocks><block type='integrator' name='x'/>" +
         "<block type='gain' name='g' k='" + last + "'/><block type='identifier' name='i' identifier='" + last +
         "'/></blocks><connections><connect from='x.y' to='g.u'/><connect from='g.y' to='x.u'/></connections>"
         "</diagram>";
}

// bench/large_inputs.sh's `bodies`: each body slides on the one before, held by a spring
std::string Sliders(int n) {
  std::string xml = "<diagram name='line'><mechanism name='m'>\n";
  for (int i = 1; i <= n; ++i) {
    const std::string b = "b" + std::to_string(i), j = "j" + std::to_string(i);
    xml += "<body name='" + b + "' mass='1' inertia='1 1 1'/>\n<joint name='" + j +
           "' type='translational' body1='" + (i == 1 ? std::string("Base0") : "b" + std::to_string(i - 1)) +
           "' body2='" + b + "' axis='1 0 0'/>\n<joint_force name='f" + std::to_string(i) +
           "' type='linear' dof='" + j + "' c='100'/>\n";
  }
  return xml + "</mechanism></diagram>";
}

double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Cost {
  double seconds = 1e300;  // the fastest of the repetitions
  long long bytes = 0;     // asked of malloc while loading (the same every time)
};

Cost Load(const Generator& generate, int n) {
  const std::string xml = generate(n);
  Cost cost;
  for (int repetition = 0; repetition < 3; ++repetition) {
    g_bytes = 0;
    const double start = CpuSeconds();
    g_counting = true;
    {
      const auto loaded = mechflow::testing::LoadXml(xml);
      g_counting = false;
    }
    cost.seconds = std::min(cost.seconds, CpuSeconds() - start);
    cost.bytes = g_bytes;
  }
  return cost;
}

// Ten times the size costs less than 30 times the time (linear: 10,
// quadratic: 100) and 15 times the bytes.
void ExpectLinear(const Generator& generate, int n, bool timed = true) {
  const Cost small = Load(generate, n), large = Load(generate, 10 * n);
  if (timed) {
    EXPECT_LT(large.seconds, 30 * small.seconds) << n << ": " << small.seconds << " s, " << 10 * n << ": "
                                                 << large.seconds << " s";
  }
  if (kMallocCounted) {
    EXPECT_LT(large.bytes, 15 * small.bytes) << n << ": " << small.bytes << " bytes, " << 10 * n << ": "
                                             << large.bytes << " bytes";
  }
}

TEST(LargeInputGrowth, IdentifiersDefinedByNumbers) {
  ExpectLinear([](int n) { return Identifiers(n, false); }, 2000);
}

TEST(LargeInputGrowth, IdentifiersEachAnExpressionOfThePrevious) {
  ExpectLinear([](int n) { return Identifiers(n, true); }, 1000);
}

// Bytes only: the mechanism block's rate pairs are still checked pair against
// pair (Block::DeclareRatePair, quadratic but small: 5 % of loading 20000 sliders).
TEST(LargeInputGrowth, LineOfSliders) { ExpectLinear(Sliders, 500, /*timed=*/false); }

}  // namespace
}  // namespace mechflow::diagrams
