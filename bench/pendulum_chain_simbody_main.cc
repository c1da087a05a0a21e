// One run of P4's chain with Simbody, in a process of its own: Simbody's
// CPODES carries its own copy of SUNDIALS' N_Vector functions, which the
// dynamic linker would resolve to CVODE's in a process that has both.
// bench_pendulum_chain runs this for its Simbody contenders.
//
// Usage: bench_pendulum_chain_simbody N rkm|bdf ACCURACY T_END OUTPUTS
// Prints one line: seconds steps realizations theta_1..theta_N omega_1..omega_N

#include <cstdio>
#include <cstdlib>
#include <string>

#include "bench/pendulum_chain_simbody.h"

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: %s N rkm|bdf ACCURACY T_END OUTPUTS\n", argv[0]);
    return 2;
  }
  using mechflow::bench::SimbodyIntegrator;
  const int n = std::atoi(argv[1]);
  const std::string kind = argv[2];
  if (n < 1 || (kind != "rkm" && kind != "bdf")) {
    std::fprintf(stderr, "%s: N must be >= 1 and the integrator rkm or bdf\n", argv[0]);
    return 2;
  }
  try {
    const mechflow::bench::SimbodyChain chain(n, 1.0, 1.0, 9.81);
    const auto r = chain.Run(kind == "bdf" ? SimbodyIntegrator::kCpodes : SimbodyIntegrator::kRungeKuttaMerson,
                             std::atof(argv[3]), std::atof(argv[4]), std::atoi(argv[5]));
    std::printf("%.9g %ld %ld", r.seconds, r.steps, r.realizations);
    for (int i = 0; i < n; ++i) std::printf(" %.17g", r.theta(i));
    for (int i = 0; i < n; ++i) std::printf(" %.17g", r.omega(i));
    std::printf("\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
    return 1;
  }
  return 0;
}
