// Energy sensors against independent computations: the
// kinetic energy of all bodies equals v^T M v / 2 with M from the
// composite-rigid-body algorithm, and the potential energy's gradient is the
// gravity term of inverse dynamics at rest.
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "mech/dynamics.h"
#include "mech/errors.h"
#include "mech/mechanism.h"
#include "mech/sensor.h"
#include "tests/mech/mech_test_util.h"

namespace mechflow::mech {
namespace {

double Sensor(const Mechanism& mechanism, MechanismWorkspace* ws, const std::vector<double>& x, SensorKind kind,
              int body = -1) {
  SensorSpec spec;
  spec.kind = kind;
  spec.index = body;
  CheckSensor(mechanism, spec);
  EvaluatePositions(mechanism, 0.0, x, ws);
  double out = 0.0;
  EvaluateSensor(mechanism, *ws, x, spec, {&out, 1});
  return out;
}

TEST(EnergySensorTest, KineticEnergyIsHalfVTransposeMV) {
  const auto model = testing::MixedTree();
  const Mechanism mechanism(model, {}, {});
  MechanismWorkspace ws(mechanism);
  Kinematics kin(*model);
  DynamicsWorkspace dyn(*model);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<double> q, v;
    testing::RandomState(*model, &rng, &q, &v);
    UpdateKinematics(*model, 0.0, q, v, &kin);
    Eigen::MatrixXd M;
    MassMatrix(*model, kin, &M, &dyn);
    const Eigen::Map<const Eigen::VectorXd> vv(v.data(), model->nv());
    std::vector<double> x(q);
    x.insert(x.end(), v.begin(), v.end());
    const double whole = Sensor(mechanism, &ws, x, SensorKind::kKineticEnergy);
    EXPECT_NEAR(whole, 0.5 * vv.dot(M * vv), 1e-12 * (1 + whole)) << trial;
    double sum = 0.0;
    for (int b = 1; b < model->num_bodies(); ++b) sum += Sensor(mechanism, &ws, x, SensorKind::kKineticEnergy, b);
    EXPECT_NEAR(sum, whole, 1e-12 * (1 + whole));
  }
}

TEST(EnergySensorTest, PotentialEnergyGradientIsTheGravityTerm) {
  const auto model = testing::MixedTree();
  const Mechanism mechanism(model, {}, {});
  MechanismWorkspace ws(mechanism);
  Kinematics kin(*model);
  DynamicsWorkspace dyn(*model);
  std::mt19937 rng(5);
  std::vector<double> q, v;
  testing::RandomState(*model, &rng, &q, &v);
  std::fill(v.begin(), v.end(), 0.0);
  UpdateKinematics(*model, 0.0, q, v, &kin);
  // at rest with v' = 0, inverse dynamics gives tau = dV/dq
  std::vector<double> zero(model->nv(), 0.0), tau(model->nv());
  const std::vector<Vec6> none(model->segments().size(), Vec6::Zero());
  InverseDynamics(*model, kin, zero, none, tau, &dyn);
  int checked = 0;
  for (const Dof& dof : model->dofs()) {
    const double h = 1e-6;
    std::vector<double> x(q);
    x.insert(x.end(), v.begin(), v.end());
    x[dof.q_index] += h;
    const double up = Sensor(mechanism, &ws, x, SensorKind::kPotentialEnergy);
    x[dof.q_index] -= 2 * h;
    const double down = Sensor(mechanism, &ws, x, SensorKind::kPotentialEnergy);
    EXPECT_NEAR((up - down) / (2 * h), tau[dof.v_index], 1e-7 * (1 + std::abs(tau[dof.v_index]))) << dof.name;
    ++checked;
  }
  EXPECT_GT(checked, 2);
}

TEST(EnergySensorTest, ABodyIndexOutOfRangeIsAnInputError) {
  const auto model = testing::MixedTree();
  const Mechanism mechanism(model, {}, {});
  SensorSpec spec;
  spec.kind = SensorKind::kPotentialEnergy;
  spec.index = model->num_bodies();
  EXPECT_THROW(CheckSensor(mechanism, spec), InputError);
}

}  // namespace
}  // namespace mechflow::mech
