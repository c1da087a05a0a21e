#include "bench/pendulum_chain_simbody.h"

#include <chrono>
#include <stdexcept>
#include <vector>

#include <Simbody.h>

namespace mechflow::bench {

// Rods along +x, pins about z, gravity along -y: the diagram's plane turned,
// with the same signs (a rod falling from horizontal turns negative).
struct SimbodyChain::System {
  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter{system};
  SimTK::GeneralForceSubsystem forces{system};
  std::vector<SimTK::MobilizedBody::Pin> pins;
};

SimbodyChain::SimbodyChain(int n, double mass, double length, double g) : system_(new System), n_(n) {
  using namespace SimTK;
  Force::Gravity(system_->forces, system_->matter, -YAxis, g);
  const Vec3 centre(length / 2, 0, 0);
  const Inertia about_centre(Vec3(1e-6, mass * length * length / 12, mass * length * length / 12));
  const Body::Rigid rod(MassProperties(mass, centre, about_centre.shiftFromMassCenter(centre, mass)));
  system_->pins.reserve(n);
  for (int i = 0; i < n; ++i) {
    MobilizedBody& parent = i == 0 ? static_cast<MobilizedBody&>(system_->matter.updGround()) : system_->pins.back();
    system_->pins.emplace_back(parent, Transform(Vec3(i == 0 ? 0.0 : length, 0, 0)), rod, Transform());
  }
  system_->system.realizeTopology();
}

SimbodyChain::~SimbodyChain() = default;

SimbodyRunResult SimbodyChain::Run(SimbodyIntegrator kind, double accuracy, double t_end, int num_outputs) const {
  using namespace SimTK;
  using Clock = std::chrono::steady_clock;
  std::vector<double> rows(static_cast<std::size_t>(num_outputs + 1) * n_);  // q at every output time
  const auto start = Clock::now();
  State state = system_->system.getDefaultState();
  system_->system.realizeModel(state);
  std::unique_ptr<Integrator> integrator;
  if (kind == SimbodyIntegrator::kCpodes) integrator = std::make_unique<CPodesIntegrator>(system_->system);
  else integrator = std::make_unique<RungeKuttaMersonIntegrator>(system_->system);
  integrator->setAccuracy(accuracy);
  integrator->initialize(state);
  for (int k = 0; k <= num_outputs; ++k) {
    const double t = t_end * k / num_outputs;
    while (integrator->getTime() < t) {
      const Integrator::SuccessfulStepStatus status = integrator->stepTo(t);
      if (status == Integrator::EndOfSimulation) throw std::runtime_error("Simbody integration ended early");
    }
    const Vector& q = integrator->getState().getQ();
    for (int i = 0; i < n_; ++i) rows[static_cast<std::size_t>(k) * n_ + i] = q[i];
  }
  SimbodyRunResult r;
  r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  r.steps = integrator->getNumStepsTaken();
  r.realizations = integrator->getNumRealizations();
  const State& end = integrator->getState();
  r.theta.resize(n_);
  r.omega.resize(n_);
  double theta = 0.0, omega = 0.0;
  for (int i = 0; i < n_; ++i) {
    theta += end.getQ()[i];
    omega += end.getU()[i];
    r.theta(i) = theta;
    r.omega(i) = omega;
  }
  return r;
}

}  // namespace mechflow::bench
