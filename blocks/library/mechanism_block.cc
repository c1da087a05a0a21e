#include "blocks/library/mechanism_block.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "blocks/library/mechanism_sparsity.h"
#include "mech/errors.h"

namespace mechflow::blocks {
namespace {

std::vector<std::string> StateNames(const mech::Mechanism& mechanism) {
  const mech::Model& model = mechanism.model();
  std::vector<std::string> names(mechanism.num_states());
  for (const mech::Dof& dof : model.dofs()) {
    names[dof.q_index] = "q:" + dof.name;
    names[model.nq() + dof.v_index] = "v:" + dof.name;
  }
  for (const mech::Segment& seg : model.segments()) {
    if (seg.motion != mech::SegmentMotion::kFree) continue;
    const std::string& joint = model.joints()[seg.joint].name;
    const char* q_names[7] = {"x", "y", "z", "qw", "qx", "qy", "qz"};
    const char* v_names[6] = {"wx", "wy", "wz", "vx", "vy", "vz"};
    for (int k = 0; k < 7; ++k) names[seg.q_index + k] = joint + "." + q_names[k];
    for (int k = 0; k < 6; ++k) names[model.nq() + seg.v_index + k] = joint + "." + v_names[k];
  }
  for (int e = 0; e < mechanism.num_elements(); ++e)
    for (int k = 0; k < mechanism.element(e).num_states(); ++k)
      names[mechanism.state_offset(e) + k] = mechanism.element(e).name() + ".s" + std::to_string(k);
  return names;
}

}  // namespace

struct MechanismBlock::Scratch final : BlockScratch {
  explicit Scratch(const mech::Mechanism& mechanism)
      : ws(mechanism),
        inputs(mechanism.num_inputs(), 0.0),
        projected(mechanism.num_states(), 0.0),
        xdot(mechanism.num_states(), 0.0) {}

  // After modes or states changed outside an evaluation: nothing cached holds.
  void ForgetEvaluations() {
    positions_at = full_at = elements_with_inputs_at = sensed_at = sensed_with_inputs_at = ~std::uint64_t{0};
  }

  mech::MechanismWorkspace ws;
  std::vector<double> inputs, projected, xdot;
  // The evaluation each result was last computed at. sensed_at: the
  // sensed elements, perhaps with inputs not yet computed in it.
  std::uint64_t positions_at = ~std::uint64_t{0}, full_at = ~std::uint64_t{0},
                elements_with_inputs_at = ~std::uint64_t{0}, sensed_at = ~std::uint64_t{0},
                sensed_with_inputs_at = ~std::uint64_t{0};
  double worst_residual = 0.0;
  bool initial_state_pending = false;  // driven segments: redo InitialState with the drives
  std::vector<mech::SlidingJacobian::Entry> jacobian_entries;
};

MechanismBlock::MechanismBlock(std::string name, std::shared_ptr<const mech::Mechanism> mechanism,
                               std::vector<mech::SensorSpec> sensors)
    : Block("mechanism", std::move(name)),
      mechanism_(std::move(mechanism)),
      sensors_(std::move(sensors)) {
  for (int i = 0; i < mechanism_->num_inputs(); ++i) DeclareInputPort(mechanism_->input_name(i));
  for (const std::string& signal : mechanism_->model().drive_signals()) {
    if (FindInput(signal) >= 0)
      throw InputError("mechanism '" + this->name() + "': the driving signal '" + signal +
                       "' has the name of an <input>; give the drive another name");
    DeclareInputPort(signal, 3);  // q, q', q''
  }
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    const mech::SensorSpec& sensor = sensors_[i];
    mech::CheckSensor(*mechanism_, sensor);
    for (std::size_t j = 0; j < i; ++j)
      if (sensors_[j].name == sensor.name)
        throw InputError((sensor.origin.empty() ? "" : sensor.origin + ": ") + "mechanism '" + this->name() +
                         "' has a second sensor named '" + sensor.name + "'");
    DeclareOutputPort(sensor.name, mech::SensorWidth(sensor));
  }
  // Positions, velocities and angles come from the state alone; element
  // outputs depend on the inputs only when the element's parameters follow
  // them (a spring force may feed a friction force back without a loop).
  for (int out = 0; out < num_outputs(); ++out) {
    if (mech::SensorDependsOnInputs(*mechanism_, sensors_[out])) continue;
    for (int in = 0; in < mechanism_->num_inputs(); ++in) SetFeedthrough(in, out, false);
  }
  const std::vector<std::string> names = StateNames(*mechanism_);
  for (const std::string& state : names) DeclareContinuousStates(1, state);
  // a joint coordinate's rate is its velocity (mech::CoordinateRates)
  for (const mech::Dof& dof : mechanism_->model().dofs())
    DeclareRatePair(dof.q_index, mechanism_->model().nq() + dof.v_index);
  DeclareDiscreteStates(mechanism_->num_modes());
  for (int e = 0; e < mechanism_->num_elements(); ++e)
    for (int k = 0; k < mechanism_->element(e).num_crossings(); ++k) {
      const mech::Crossing c = mechanism_->element(e).crossing_direction(k);
      DeclareZeroCrossing(c == mech::Crossing::kRising    ? CrossingDirection::kRising
                          : c == mech::Crossing::kFalling ? CrossingDirection::kFalling
                                                          : CrossingDirection::kEither);
    }
  if (!mechanism_->constraints().empty() || mechanism_->model().has_quaternions() ||
      (!mechanism_->exact_stick_elements().empty()))
    DeclareProjection();
  const mech::Model& model = mechanism_->model();
  for (const auto& sensor : sensors_) {
    routes_.push_back(RouteOf(sensor));
    slots_.push_back(sensor.kind == mech::SensorKind::kCoordinate ? model.dofs()[sensor.index].q_index
                     : sensor.kind == mech::SensorKind::kVelocity ? model.nq() + model.dofs()[sensor.index].v_index
                     : sensor.kind == mech::SensorKind::kElement
                         ? mechanism_->sensor_offset(sensor.index) + sensor.element_sensor
                         : -1);
    if (sensor.kind == mech::SensorKind::kReactionForce || sensor.kind == mech::SensorKind::kReactionTorque)
      want_reactions_ = true;
    if (sensor.kind == mech::SensorKind::kElement) sensed_elements_.push_back(sensor.index);
  }
  std::sort(sensed_elements_.begin(), sensed_elements_.end());
  sensed_elements_.erase(std::unique(sensed_elements_.begin(), sensed_elements_.end()), sensed_elements_.end());
  if (mech::SlidingJacobian::Unavailable(*mechanism_).empty()) jacobian_.emplace(*mechanism_);
}

std::unique_ptr<BlockScratch> MechanismBlock::MakeScratch() const {
  auto s = std::make_unique<Scratch>(*mechanism_);
  s->ws.want_reactions = want_reactions_;
  return s;
}

const BlockSparsity* MechanismBlock::sparsity() const {
  std::call_once(sparsity_once_, [this] { sparsity_ = MechanismSparsity(*mechanism_, sensors_); });
  return sparsity_ ? &*sparsity_ : nullptr;
}

std::span<const double> MechanismBlock::Inputs(const BlockContext& ctx, Scratch& s) const {
  for (int i = 0; i < mechanism_->num_inputs(); ++i) s.inputs[i] = ctx.input_scalar(i);
  ReadDrives(ctx, s);
  return s.inputs;
}

void MechanismBlock::ReadDrives(const BlockContext& ctx, Scratch& s) const {
  const int first = mechanism_->num_inputs();
  for (std::size_t k = 0; k < s.ws.kin.drives.size(); ++k) {
    const std::span<const double> jet = ctx.input(first + static_cast<int>(k));
    s.ws.kin.drives[k] = {jet[0], jet[1], jet[2]};
  }
}

void MechanismBlock::DoInitialize(const BlockContext& ctx) const {
  Scratch& s = ctx.scratch<Scratch>();
  // Inputs are not valid yet: elements initialise with inputs at zero, and
  // driven segments at zero until the first mode update (below).
  std::fill(s.inputs.begin(), s.inputs.end(), 0.0);
  std::fill(s.ws.kin.drives.begin(), s.ws.kin.drives.end(), mech::Jet{});
  mech::InitialState(*mechanism_, s.inputs, ctx.state(), ctx.discrete(), &s.ws);
  s.ForgetEvaluations();
  s.worst_residual = 0.0;
  s.initial_state_pending = !s.ws.kin.drives.empty();
}

void MechanismBlock::EnsureEvaluated(const BlockContext& ctx, Scratch& s, bool full) const {
  const std::uint64_t now = ctx.evaluation();
  if (full) {
    if (s.full_at == now) return;
    // x' is kept: CalcDerivatives in the same evaluation reuses it
    mech::EvaluateMechanism(*mechanism_, ctx.time(), ctx.state(), Inputs(ctx, s), ctx.discrete(), &s.ws, s.xdot);
    s.full_at = s.positions_at = now;
  } else {
    if (s.positions_at == now || s.full_at == now) return;
    ReadDrives(ctx, s);
    mech::EvaluatePositions(*mechanism_, ctx.time(), ctx.state(), &s.ws);
    s.positions_at = now;
  }
}

bool MechanismBlock::StuckExactly(const BlockContext& ctx, const Scratch& s) const {
  if (mechanism_->exact_stick_elements().empty()) return false;
  return mech::AnyStuckExactly(*mechanism_, ctx.time(), ctx.state(), ctx.discrete(), s.ws);
}

void MechanismBlock::EvaluateElementsWithInputs(const BlockContext& ctx, Scratch& s) const {
  const std::uint64_t now = ctx.evaluation();
  if (s.full_at == now || s.elements_with_inputs_at == now) return;
  mech::EvaluateElements(*mechanism_, ctx.time(), ctx.state(), Inputs(ctx, s), ctx.discrete(), &s.ws, {});
  s.elements_with_inputs_at = s.positions_at = now;
}

void MechanismBlock::EvaluateSensedElements(const BlockContext& ctx, Scratch& s, bool inputs_computed) const {
  const std::uint64_t now = ctx.evaluation();
  if (s.full_at == now || s.elements_with_inputs_at == now || s.sensed_with_inputs_at == now) return;
  if (!inputs_computed && s.sensed_at == now) return;
  const std::span<const double> inputs = Inputs(ctx, s);
  // another port of this evaluation may have computed the kinematics
  if (s.positions_at != now) mech::EvaluatePositions(*mechanism_, ctx.time(), ctx.state(), &s.ws);
  mech::EvaluateSensedElements(*mechanism_, ctx.time(), ctx.state(), inputs, ctx.discrete(), &s.ws, sensed_elements_);
  s.sensed_at = s.positions_at = now;
  if (inputs_computed) s.sensed_with_inputs_at = now;
}

MechanismBlock::PortRoute MechanismBlock::RouteOf(const mech::SensorSpec& sensor) const {
  if (mech::SensorReadsStateOnly(sensor)) return PortRoute::kState;
  if (sensor.kind != mech::SensorKind::kElement)
    return mech::SensorNeedsFullEvaluation(sensor) ? PortRoute::kSolve : PortRoute::kPositions;
  return !mech::SensorDependsOnInputs(*mechanism_, sensor) && num_inputs() > 0 ? PortRoute::kElementBeforeInputs
                                                                                : PortRoute::kElement;
}

void MechanismBlock::DoCalcOutput(int port, const BlockContext& ctx) const {
  Scratch& s = ctx.scratch<Scratch>();
  switch (routes_[port]) {
    case PortRoute::kState:
      ctx.output(port)[0] = ctx.state()[slots_[port]];
      return;
    case PortRoute::kElementBeforeInputs:
      // Its inputs may not be computed yet in this evaluation (it does not
      // feed through): evaluate the sensed elements only, and keep no solve
      // cached.
      EvaluateSensedElements(ctx, s, false);
      break;
    case PortRoute::kElement:
      // An output row or a root check: no derivatives will reuse a solve, and
      // no holding force needs one; the sensed elements alone give the
      // element's values (its inputs feed through, so they are computed).
      // Else the full solve: in a right-hand side, its derivatives and
      // crossings reuse it, so the elements are evaluated once.
      if (!ctx.derivatives_follow() && !StuckExactly(ctx, s))
        EvaluateSensedElements(ctx, s, true);
      else
        EnsureEvaluated(ctx, s, true);
      break;
    case PortRoute::kPositions:
      EnsureEvaluated(ctx, s, false);
      break;
    case PortRoute::kSolve:
      EnsureEvaluated(ctx, s, true);
      break;
  }
  if (slots_[port] >= 0) {  // an element's sensor: copied as mech::EvaluateSensor would
    ctx.output(port)[0] = s.ws.sensors[slots_[port]];
    return;
  }
  mech::EvaluateSensor(*mechanism_, s.ws, ctx.state(), sensors_[port], ctx.output(port));
}

void MechanismBlock::DoCalcDerivatives(const BlockContext& ctx) const {
  Scratch& s = ctx.scratch<Scratch>();
  // An output port of this evaluation may have solved the same system already
  // (the inputs cannot have changed: every output is computed before any
  // derivative).
  if (s.full_at == ctx.evaluation()) {
    std::copy(s.xdot.begin(), s.xdot.end(), ctx.derivative().begin());
    return;
  }
  mech::EvaluateMechanism(*mechanism_, ctx.time(), ctx.state(), Inputs(ctx, s), ctx.discrete(), &s.ws,
                          ctx.derivative());
  std::copy(ctx.derivative().begin(), ctx.derivative().end(), s.xdot.begin());
  s.full_at = s.positions_at = ctx.evaluation();
}

std::string MechanismBlock::StateJacobianUnavailable() const {
  const std::string why = mech::SlidingJacobian::Unavailable(*mechanism_);
  return why.empty() ? why : "mechanism '" + name() + "' is not a sliding one: " + why;
}

void MechanismBlock::CalcStateJacobian(const BlockContext& ctx, std::vector<JacobianEntry>* entries) const {
  Scratch& s = ctx.scratch<Scratch>();
  if (!jacobian_) throw std::logic_error("mechanism '" + name() + "': " + StateJacobianUnavailable());
  EvaluateElementsWithInputs(ctx, s);
  jacobian_->Evaluate(*mechanism_, ctx.time(), ctx.state(), ctx.discrete(), s.ws, &s.jacobian_entries);
  entries->clear();
  for (const auto& [row, column, value] : s.jacobian_entries) entries->push_back({row, column, value});
}

void MechanismBlock::DoCalcZeroCrossings(const BlockContext& ctx) const {
  Scratch& s = ctx.scratch<Scratch>();
  // The crossings read positions, velocities, element states and parameters
  // (of t and the inputs, all computed by now), not loads or accelerations:
  // the kinematics are enough when no evaluation of this one is at hand --
  // unless an element sticks exactly, whose holding force is a solve's.
  const std::uint64_t now = ctx.evaluation();
  if (StuckExactly(ctx, s)) {
    EnsureEvaluated(ctx, s, true);
  } else if (s.full_at != now && s.elements_with_inputs_at != now && s.sensed_with_inputs_at != now) {
    mech::EvaluateForCrossings(*mechanism_, ctx.time(), ctx.state(), Inputs(ctx, s), &s.ws);
    s.positions_at = now;
  }
  mech::EvaluateCrossings(*mechanism_, ctx.state(), ctx.discrete(), &s.ws, ctx.zero_crossings());
}

void MechanismBlock::DoZeroCrossing(int index, int direction, const BlockContext& ctx) const {
  Scratch& s = ctx.scratch<Scratch>();
  EnsureEvaluated(ctx, s, true);
  mech::ApplyCrossing(*mechanism_, index, direction, ctx.state(), ctx.discrete(), &s.ws);
  s.ForgetEvaluations();
}

bool MechanismBlock::DoUpdateModes(const BlockContext& ctx) const {
  Scratch& s = ctx.scratch<Scratch>();
  if (s.initial_state_pending) {
    // The first update with valid inputs: assemble the loops and start the
    // elements at the drives' starting values (DoInitialize saw zeros).
    s.initial_state_pending = false;
    mech::InitialState(*mechanism_, Inputs(ctx, s), ctx.state(), ctx.discrete(), &s.ws);
    s.ForgetEvaluations();
    mech::UpdateElementModes(*mechanism_, ctx.time(), ctx.state(), Inputs(ctx, s), ctx.discrete(), &s.ws);
    return true;
  }
  if (mechanism_->num_modes() == 0) return false;
  const bool changed =
      mech::UpdateElementModes(*mechanism_, ctx.time(), ctx.state(), Inputs(ctx, s), ctx.discrete(), &s.ws);
  s.ForgetEvaluations();
  return changed;
}

bool MechanismBlock::DoUpdateModesAtRest(const BlockContext& ctx) const {
  Scratch& s = ctx.scratch<Scratch>();
  if (s.initial_state_pending || mechanism_->num_modes() == 0) return DoUpdateModes(ctx);
  const bool changed =
      mech::ElementModesAtRest(*mechanism_, ctx.time(), ctx.state(), Inputs(ctx, s), ctx.discrete(), &s.ws);
  s.ForgetEvaluations();
  return changed;
}

void MechanismBlock::DoProject(const BlockContext& ctx, std::span<double> correction, std::span<double>,
                               std::span<const double> weights) const {
  Scratch& s = ctx.scratch<Scratch>();
  const mech::Model& model = mechanism_->model();
  const std::span<const double> x = ctx.state();
  std::copy(x.begin(), x.end(), s.projected.begin());
  std::span<double> q(s.projected.data(), model.nq()), v(s.projected.data() + model.nq(), model.nv());
  // Unit quaternions first (their projection is exact), then the loops.
  for (const mech::Segment& seg : model.segments()) {
    if (seg.motion != mech::SegmentMotion::kFree) continue;
    double norm = 0.0;
    for (int k = 3; k < 7; ++k) norm += q[seg.q_index + k] * q[seg.q_index + k];
    norm = std::sqrt(norm);
    if (!(norm > 0.0) || !std::isfinite(norm))
      throw SimulationError("mechanism '" + name() + "': the quaternion of joint '" +
                            model.joints()[seg.joint].name + "' cannot be normalised (norm " +
                            std::to_string(norm) + ")");
    for (int k = 3; k < 7; ++k) q[seg.q_index + k] /= norm;
  }
  if (!mechanism_->constraints().empty()) {
    ReadDrives(ctx, s);
    mech::UpdateKinematics(model, ctx.time(), q, v, &s.ws.kin);
    mechanism_->constraints().Residual(model, s.ws.kin, &s.ws.constraint.phi);
    s.worst_residual = std::max(s.worst_residual, s.ws.constraint.phi.lpNorm<Eigen::Infinity>());
    // To round-off, always: a projection that skipped small residuals would
    // move the state by jumps of its tolerance, which CVODE adds to its
    // history (at rtol 1e-12 that stalled the step size).
    // The velocities' tolerance as the error test weighs them (RMS): near a
    // dead centre the projections leave alone what round-off cannot resolve
    // within it (mech/constraint_solve.h).
    double velocity_tolerance = 0.0;
    if (!weights.empty() && model.nv() > 0) {
      double sum = 0.0;
      for (int i = 0; i < model.nv(); ++i) sum += weights[model.nq() + i] * weights[model.nq() + i];
      if (sum > 0.0) velocity_tolerance = std::sqrt(model.nv() / sum);
    }
    const double after = mech::ProjectPositions(model, mechanism_->constraints(), ctx.time(), q, v, 1e-16, 5,
                                                &s.ws.kin, &s.ws.constraint, velocity_tolerance);
    if (!std::isfinite(after))
      throw SimulationError("mechanism '" + name() + "': projection onto the loop constraints failed at t = " +
                            std::to_string(ctx.time()));
    mech::ProjectVelocities(model, mechanism_->constraints(), ctx.time(), q, v, &s.ws.kin, &s.ws.constraint,
                            velocity_tolerance);
  }
  // the velocities of the holds that stick exactly: zero, not the integrator's
  // drift; the slips' directions: those of this step's end
  if (!mechanism_->exact_stick_elements().empty()) {
    if (mechanism_->constraints().empty()) ReadDrives(ctx, s);
    mech::ZeroStuckVelocities(*mechanism_, ctx.time(), s.projected, ctx.discrete(), &s.ws);
    mech::FollowSlips(*mechanism_, ctx.time(), s.projected, ctx.discrete(), &s.ws);
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    correction[i] = s.projected[i] - x[i];
    if (!std::isfinite(correction[i]))
      throw SimulationError("mechanism '" + name() + "': projection gave a non-finite state at t = " +
                            std::to_string(ctx.time()));
  }
  s.ForgetEvaluations();
}

std::string MechanismBlock::CrossingName(int index, int direction) const {
  for (int i = 0; i < mechanism_->num_elements(); ++i) {
    const int local = index - mechanism_->crossing_offset(i);
    if (local >= 0 && local < mechanism_->element(i).num_crossings())
      return mechanism_->element(i).name() + ": " + mechanism_->element(i).CrossingName(local, direction);
  }
  return {};
}

std::string MechanismBlock::FailureNote(const BlockContext& ctx) const {
  if (mechanism_->constraints().empty()) return {};
  const Scratch& s = ctx.scratch<Scratch>();
  return mech::SingularPositionNote(mechanism_->model(), mechanism_->constraints(), s.ws.constraint);
}

double MechanismBlock::worst_constraint_residual(const Context& run, int block) const {
  const Scratch* s = RunScratch<Scratch>(run, block);
  return s ? s->worst_residual : 0.0;
}

}  // namespace mechflow::blocks
