#pragma once
// P4's pendulum chain built with Simbody (Debian's libsimbody-dev) and run by
// its own integrators: the peer a multibody user would otherwise pick. The
// same rods as bench/pendulum_chain_direct.h (1 kg, 1 m, 1/12 kg m^2 about
// the centre, 1e-6 about the rod's axis as mechflow's diagram gives it), pin
// joints, gravity 9.81, released horizontal at rest; Simbody's accuracy
// setting (a relative tolerance in its error norm) takes rtol.
//
// Only built when CMake finds Simbody (bench/CMakeLists.txt).

#include <memory>
#include <string>

#include <Eigen/Core>

namespace mechflow::bench {

enum class SimbodyIntegrator {
  kRungeKuttaMerson,  // explicit, Simbody's default
  kCpodes,            // BDF with Newton (Simbody's CVODE-derived CPODES)
};

struct SimbodyRunResult {
  double seconds = 0.0;  // integrator set-up and integration, recording every output time
  long steps = 0;
  long realizations = 0;  // evaluations of the accelerations (Simbody's realizations)
  Eigen::VectorXd theta, omega;  // absolute angles from the horizontal [rad] and rates at t_end
};

// A chain of n rods, built once (untimed); Run integrates it afresh.
class SimbodyChain {
 public:
  SimbodyChain(int n, double mass, double length, double g);
  ~SimbodyChain();
  SimbodyRunResult Run(SimbodyIntegrator integrator, double accuracy, double t_end, int num_outputs) const;

 private:
  struct System;
  std::unique_ptr<System> system_;
  int n_;
};

}  // namespace mechflow::bench
