#include "mech/mechanism.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mech/errors.h"
#include "mech/mechanism_parts.h"

namespace mechflow::mech {
ElementContext MakeElementContext(const Mechanism& mechanism, double t, std::span<const double> x,
                                  std::span<const double> modes, const MechanismWorkspace& ws, int e) {
  const Model& model = mechanism.model();
  const ForceElement& element = mechanism.element(e);
  ElementContext ctx;
  ctx.t = t;
  ctx.model = &model;
  ctx.kin = &ws.kin;
  ctx.q = x.subspan(0, model.nq());
  ctx.v = x.subspan(model.nq(), model.nv());
  ctx.parameter_args = ws.parameter_args;
  ctx.state = x.subspan(mechanism.state_offset(e), element.num_states());
  ctx.modes = modes.empty() ? modes : modes.subspan(mechanism.mode_offset(e), element.num_modes());
  if (element.num_holds() > 0)
    ctx.stick_forces = std::span<const double>(ws.stick.force).subspan(mechanism.hold_offset(e), element.num_holds());
  ctx.scratch = ws.element_scratch[e].get();
  return ctx;
}

namespace {

// Segment loads with the constraint wrenches (lambda) applied to both sides.
void AddConstraintLoads(const Mechanism& mechanism, MechanismWorkspace* ws) {
  const Model& model = mechanism.model();
  const Constraints& constraints = mechanism.constraints();
  auto& loads = ws->constraint.loads;
  for (std::size_t s = 0; s < loads.size(); ++s) loads[s] = ws->loads.segment_loads()[s];
  auto add = [&](int s, const Vec3& point, const Vec3& force, const Vec3& torque) {
    if (s == kGround) return;
    const Pose& pose = ws->kin.pose[s];
    const Vec3 f = pose.R.transpose() * force;
    const Vec3 r = pose.R.transpose() * (point - pose.p);
    loads[s].head<3>() += pose.R.transpose() * torque + r.cross(f);
    loads[s].tail<3>() += f;
  };
  for (int k = 0; k < static_cast<int>(constraints.cut_joints().size()); ++k) {
    const Constraints::Load load = constraints.LoadOf(model, ws->kin, ws->constraint.lambda, k);
    add(load.segment_b, load.point_b, load.force, load.torque);
    add(load.segment_a, load.point_a, -load.force, -load.torque);
  }
}

void SolveConstrained(const Mechanism& mechanism, MechanismWorkspace* ws) {
  const Model& model = mechanism.model();
  ConstraintWorkspace& c = ws->constraint;
  // f = tau - h(q, v, external): the accelerations' right-hand side (in c.h)
  InverseDynamics(model, ws->kin, c.zero, ws->loads.segment_loads(), c.h, &ws->dyn);
  for (int i = 0; i < model.nv(); ++i) c.h[i] = ws->loads.generalized()[i] - c.h[i];
  MassMatrix(model, ws->kin, &c.M, &ws->dyn);
  mechanism.constraints().Jacobian(model, ws->kin, &c.J);
  mechanism.constraints().AccelerationBias(model, ws->kin, &c.scratch, &c.bias);
  SolveConstrainedAccelerations(c.h, ws->vdot, &c);
}

// The power the joints of time-driven segments transmit along their motion:
// the force across the joint (Newton-Euler's, after the final pass) times
// the segment's velocity relative to its parent.
double DrivePower(const Model& model, const MechanismWorkspace& ws) {
  double power = 0.0;
  for (int i = 0; i < static_cast<int>(model.segments().size()); ++i) {
    const Segment& seg = model.segments()[i];
    if (seg.drive != SegmentDrive::kTime) continue;
    Vec6 relative = ws.kin.velocity[i];
    if (seg.parent != kGround) relative -= ws.kin.X[i].Motion(ws.kin.velocity[seg.parent]);
    power += ws.dyn.force[i].dot(relative);
  }
  return power;
}

// A loop whose own coordinates are all fixed by its constraint (and that no
// prescribed motion drives) locks its bodies: almost always a modelling error
// (two hinges on different axes, a slider across a hinge).
void CheckLoopsLeaveMotion(const Mechanism& mechanism, MechanismWorkspace* ws) {
  const Model& model = mechanism.model();
  const Constraints& constraints = mechanism.constraints();
  constraints.Jacobian(model, ws->kin, &ws->constraint.J);
  const Eigen::MatrixXd& J = ws->constraint.J;
  for (int k = 0; k < static_cast<int>(constraints.cut_joints().size()); ++k) {
    // a weld cut has six rows, a CV joint four
    const auto rows = J.middleRows(constraints.row(k), constraints.rows(k));
    std::vector<int> columns;
    for (int c = 0; c < model.nv(); ++c)
      if (rows.col(c).lpNorm<Eigen::Infinity>() > 1e-12) columns.push_back(c);
    if (columns.empty()) continue;  // it moves nothing (two welds of one body): nothing to lock
    Eigen::MatrixXd sub(rows.rows(), columns.size());
    for (std::size_t i = 0; i < columns.size(); ++i) sub.col(i) = rows.col(columns[i]);
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(sub);
    cod.setThreshold(1e-10);
    if (cod.rank() < static_cast<int>(columns.size())) continue;
    const Joint& cut = model.joints()[constraints.cut_joints()[k]];
    // Bodies moved by the locked coordinates, and whether time drives the loop.
    std::vector<std::string> bodies;
    bool driven = false;
    for (const Segment& seg : model.segments())
      if (seg.drive == SegmentDrive::kTime && !seg.ghost) driven = true;
    if (driven) continue;
    for (int c : columns)
      for (const Dof& dof : model.dofs())
        if (dof.v_index == c) {
          const std::string& name = model.bodies()[model.joints()[dof.joint].body2].name;
          if (std::find(bodies.begin(), bodies.end(), name) == bodies.end()) bodies.push_back(name);
        }
    std::ostringstream out;
    out << cut.origin << (cut.origin.empty() ? "" : ": ") << "joint '" << cut.name
        << "' over-constrains the mechanism: with it, bodies";
    for (std::size_t i = 0; i < bodies.size(); ++i) out << (i ? ", '" : " '") << bodies[i] << "'";
    out << " have no degree of freedom left (bodies '" << model.bodies()[cut.body1].name << "' and '"
        << model.bodies()[cut.body2].name << "' are already joined through other joints)";
    throw InputError(out.str());
  }
}

}  // namespace

// Element e's loads, state rates and sensors; with its work tracked, also the
// work's rate (the power of its loads) and its work sensors.
void EvaluateElement(const Mechanism& mechanism, int e, double t, std::span<const double> x,
                     std::span<const double> modes, MechanismWorkspace* ws, std::span<double> all_rates) {
  const ForceElement& element = mechanism.element(e);
  const ElementContext ctx = MakeElementContext(mechanism, t, x, modes, *ws, e);
  const std::span<double> rates = all_rates.subspan(mechanism.state_offset(e), element.num_states());
  const std::span<double> sensors =
      std::span<double>(ws->sensors).subspan(mechanism.sensor_offset(e), element.num_sensors());
  const double before = ws->loads.power();
  element.Evaluate(ctx, &ws->loads, rates, sensors);
  ws->sensors_on[e] = ws->kin.stamp;
  if (!element.tracks_work()) return;
  const double work = ctx.state[element.work_state()];
  rates[element.work_state()] = ws->loads.power() - before;
  sensors[element.work_sensor()] = work;
  if (element.stores_energy())
    sensors[element.work_sensor() + 1] =
        ws->initial_stored_energy[e] - sensors[element.energy_sensor()] - work;
}

void SetParameterArgs(double t, std::span<const double> inputs, MechanismWorkspace* ws) {
  ws->parameter_args[0] = t;
  for (std::size_t i = 0; i < inputs.size() && i + 1 < ws->parameter_args.size(); ++i)
    ws->parameter_args[i + 1] = inputs[i];
}

// Accelerations for the current loads: ws->vdot, and the segments' in ws->dyn
// (which PointAcceleration reads). `final`: also the transmitted forces that
// reaction sensors read.
void SolveDynamics(const Mechanism& mechanism, MechanismWorkspace* ws, bool final) {
  const Model& model = mechanism.model();
  if (mechanism.constraints().empty()) {
    ForwardDynamics(model, ws->kin, ws->loads.generalized(), ws->loads.segment_loads(), ws->vdot, &ws->dyn);
    if (final && (ws->want_reactions || mechanism.drive_work_state() >= 0))
      InverseDynamics(model, ws->kin, ws->vdot, ws->loads.segment_loads(), ws->constraint.h, &ws->dyn);
  } else {
    SolveConstrained(mechanism, ws);
    // Reactions and point accelerations need the segment forces of the
    // actual motion.
    AddConstraintLoads(mechanism, ws);
    InverseDynamics(model, ws->kin, ws->vdot, ws->constraint.loads, ws->constraint.h, &ws->dyn);
  }
}

Mechanism::Mechanism(std::shared_ptr<const Model> model, std::vector<std::unique_ptr<ForceElement>> elements,
                     std::vector<std::string> input_names)
    : model_(std::move(model)),
      elements_(std::move(elements)),
      input_names_(std::move(input_names)),
      constraints_(*model_, model_->initial_q()) {
  for (int i = 0; i < num_elements(); ++i) element_index_.emplace(elements_[i]->name(), i);  // the first of a name
  state_size_ = model_->nq() + model_->nv();
  for (const auto& e : elements_) {
    if (e->exact_stick()) exact_stick_.push_back(static_cast<int>(layout_.size()));
    tracks_work_ = tracks_work_ || e->tracks_work();
    layout_.push_back({state_size_, mode_size_, crossing_size_, sensor_size_, num_holds()});
    hold_element_.insert(hold_element_.end(), e->num_holds(), static_cast<int>(layout_.size()) - 1);
    state_size_ += e->num_states();
    mode_size_ += e->num_modes();
    crossing_size_ += e->num_crossings();
    sensor_size_ += e->num_sensors();
  }
}

void Mechanism::TrackDriveWork() {
  if (drive_work_state_ < 0) drive_work_state_ = state_size_++;
}

int Mechanism::FindElement(const std::string& name) const {
  const auto it = element_index_.find(name);
  return it == element_index_.end() ? -1 : it->second;
}

int Mechanism::FindInput(const std::string& name) const {
  for (int i = 0; i < num_inputs(); ++i)
    if (input_names_[i] == name) return i;
  return -1;
}

MechanismWorkspace::MechanismWorkspace(const Mechanism& mechanism)
    : kin(mechanism.model()),
      dyn(mechanism.model()),
      loads(mechanism.model()),
      loads_before_holds(mechanism.model()),
      loads_without_holds(mechanism.model()),
      constraint(mechanism.model(), mechanism.constraints()),
      stick(mechanism.num_holds()),
      vdot(mechanism.model().nv(), 0.0),
      vdot_free(mechanism.model().nv(), 0.0),
      sensors(mechanism.num_sensor_values(), 0.0),
      sensors_on(mechanism.num_elements(), ~std::uint64_t{0}),
      rates(mechanism.num_states(), 0.0),
      parameter_args(1 + mechanism.num_inputs(), 0.0),
      initial_stored_energy(mechanism.num_elements(), 0.0) {
  holding.reserve(mechanism.exact_stick_elements().size());
  for (int e = 0; e < mechanism.num_elements(); ++e) element_scratch.push_back(mechanism.element(e).MakeScratch());
}

void EvaluatePositions(const Mechanism& mechanism, double t, std::span<const double> x, MechanismWorkspace* ws) {
  const Model& model = mechanism.model();
  UpdateKinematics(model, t, x.subspan(0, model.nq()), x.subspan(model.nq(), model.nv()), &ws->kin);
  ws->accelerations_valid = false;
}

void EvaluateElements(const Mechanism& mechanism, double t, std::span<const double> x,
                      std::span<const double> inputs, std::span<const double> modes, MechanismWorkspace* ws,
                      std::span<double> xdot) {
  EvaluatePositions(mechanism, t, x, ws);
  SetParameterArgs(t, inputs, ws);
  ws->loads.Clear();
  if (mechanism.tracks_work()) ws->loads.TrackPower(x.subspan(mechanism.model().nq(), mechanism.model().nv()));
  // Elements always get somewhere to write their state rates.
  std::span<double> all_rates = xdot.empty() ? std::span<double>(ws->rates) : xdot;
  for (int e = 0; e < mechanism.num_elements(); ++e) EvaluateElement(mechanism, e, t, x, modes, ws, all_rates);
}

void EvaluateSensedElements(const Mechanism& mechanism, double t, std::span<const double> x,
                            std::span<const double> inputs, std::span<const double> modes, MechanismWorkspace* ws,
                            std::span<const int> elements) {
  SetParameterArgs(t, inputs, ws);
  if (mechanism.tracks_work()) {  // the work sensors need each element's power
    ws->loads.Clear();
    ws->loads.TrackPower(x.subspan(mechanism.model().nq(), mechanism.model().nv()));
    for (const int e : elements) EvaluateElement(mechanism, e, t, x, modes, ws, ws->rates);
    return;
  }
  // sensors alone: their loads are not wanted (a full evaluation clears the loads first)
  struct Discarding {
    Loads& loads;
    explicit Discarding(Loads& l) : loads(l) { loads.SetDiscard(true); }
    ~Discarding() { loads.SetDiscard(false); }  // also when an element throws
  } discarding(ws->loads);
  for (const int e : elements) EvaluateElement(mechanism, e, t, x, modes, ws, ws->rates);
}

void EvaluateMechanism(const Mechanism& mechanism, double t, std::span<const double> x,
                       std::span<const double> inputs, std::span<const double> modes, MechanismWorkspace* ws,
                       std::span<double> xdot) {
  const Model& model = mechanism.model();
  FindStuck(mechanism, t, x, modes, ws);
  if (ws->stick.stuck.empty()) {
    EvaluateElements(mechanism, t, x, inputs, modes, ws, xdot);
  } else {
    const std::span<double> rates = xdot.empty() ? std::span<double>(ws->rates) : xdot;
    EvaluateElementsHoldingLast(mechanism, t, x, inputs, modes, ws, rates);
    HoldStuckElements(mechanism, t, x, modes, ws, rates);
  }
  SolveDynamics(mechanism, ws, true);
  ws->accelerations_valid = true;
  if (xdot.empty()) return;
  CoordinateRates(model, x.subspan(0, model.nq()), x.subspan(model.nq(), model.nv()), xdot.subspan(0, model.nq()));
  for (int i = 0; i < model.nv(); ++i) xdot[model.nq() + i] = ws->vdot[i];
  if (mechanism.drive_work_state() >= 0) xdot[mechanism.drive_work_state()] = DrivePower(model, *ws);
}

void EvaluateForCrossings(const Mechanism& mechanism, double t, std::span<const double> x,
                          std::span<const double> inputs, MechanismWorkspace* ws) {
  EvaluatePositions(mechanism, t, x, ws);
  SetParameterArgs(t, inputs, ws);
}

void EvaluateCrossings(const Mechanism& mechanism, std::span<const double> x, std::span<const double> modes,
                       MechanismWorkspace* ws, std::span<double> values) {
  for (int e = 0; e < mechanism.num_elements(); ++e) {
    const ForceElement& element = mechanism.element(e);
    if (element.num_crossings() == 0) continue;
    ElementContext ctx = MakeElementContext(mechanism, ws->kin.time, x, modes, *ws, e);
    // evaluated on these kinematics (in the same modes: a mode change makes the caller update them)
    if (ws->sensors_on[e] == ws->kin.stamp)
      ctx.sensors = std::span<const double>(ws->sensors).subspan(mechanism.sensor_offset(e), element.num_sensors());
    element.ZeroCrossings(ctx, values.subspan(mechanism.crossing_offset(e), element.num_crossings()));
  }
}

void ApplyCrossing(const Mechanism& mechanism, int crossing, int direction, std::span<double> x,
                   std::span<double> modes, MechanismWorkspace* ws) {
  for (int e = 0; e < mechanism.num_elements(); ++e) {
    const ForceElement& element = mechanism.element(e);
    const int first = mechanism.crossing_offset(e);
    if (crossing < first || crossing >= first + element.num_crossings()) continue;
    const ElementContext ctx = MakeElementContext(mechanism, ws->kin.time, x, modes, *ws, e);
    element.OnCrossing(crossing - first, direction, ctx, x.subspan(mechanism.state_offset(e), element.num_states()),
                       modes.subspan(mechanism.mode_offset(e), element.num_modes()));
    return;
  }
}

void InitialState(const Mechanism& mechanism, std::span<const double> inputs, std::span<double> x,
                  std::span<double> modes, MechanismWorkspace* ws) {
  const Model& model = mechanism.model();
  for (int i = 0; i < model.nq(); ++i) x[i] = model.initial_q()[i];
  for (int i = 0; i < model.nv(); ++i) x[model.nq() + i] = model.initial_v()[i];
  for (int i = model.nq() + model.nv(); i < mechanism.num_states(); ++i) x[i] = 0.0;
  for (double& m : modes) m = 0.0;
  std::span<double> q = x.subspan(0, model.nq()), v = x.subspan(model.nq(), model.nv());
  const Constraints& constraints = mechanism.constraints();
  if (!constraints.empty()) {
    AssembleCutCoordinates(model, constraints, q, v, &ws->kin, &ws->constraint);
    const double residual = ProjectPositions(model, constraints, 0.0, q, v, 1e-12, 50, &ws->kin, &ws->constraint);
    if (!(residual <= 1e-9)) {
      std::ostringstream out;
      const Joint& joint = model.joints()[constraints.cut_joints()[0]];
      out << joint.origin << (joint.origin.empty() ? "" : ": ") << "the loop closed by joint '" << joint.name
          << "' cannot be assembled from the initial coordinates (residual " << residual
          << " after 50 Newton steps): check the dimensions and the initial coordinates";
      throw InputError(out.str());
    }
    AssembleCutVelocities(model, constraints, q, v, &ws->kin, &ws->constraint);
    ProjectVelocities(model, constraints, 0.0, q, v, &ws->kin, &ws->constraint);
    CheckLoopsLeaveMotion(mechanism, ws);
    RecordGenericRank(model, constraints, ws->kin, &ws->constraint);
  }
  EvaluatePositions(mechanism, 0.0, x, ws);
  SetParameterArgs(0.0, inputs, ws);
  for (int e = 0; e < mechanism.num_elements(); ++e) {
    const ForceElement& element = mechanism.element(e);
    const ElementContext ctx = MakeElementContext(mechanism, 0.0, x, modes, *ws, e);
    element.Initialize(ctx, x.subspan(mechanism.state_offset(e), element.num_states()),
                       modes.subspan(mechanism.mode_offset(e), element.num_modes()));
    if (element.tracks_work()) x[mechanism.state_offset(e) + element.work_state()] = 0.0;
  }
  // The references of the energy sensors: what is stored at the start (the
  // elements are evaluated only when one integrates its work).
  ws->initial_mechanical_energy = 0.0;
  for (int b = 1; b < model.num_bodies(); ++b)
    ws->initial_mechanical_energy += KineticEnergy(model, ws->kin, b) + PotentialEnergy(model, ws->kin, b);
  if (!mechanism.tracks_work()) return;
  EvaluateElements(mechanism, 0.0, x, inputs, modes, ws, {});
  for (int e = 0; e < mechanism.num_elements(); ++e) {
    const int energy = mechanism.element(e).energy_sensor();
    ws->initial_stored_energy[e] = energy < 0 ? 0.0 : ws->sensors[mechanism.sensor_offset(e) + energy];
  }
}

namespace {

// What the elements' mode updates read: the kinematics and parameters, and
// with exact-stick elements the holding forces of a full evaluation.
void EvaluateForModes(const Mechanism& mechanism, double t, std::span<const double> x,
                      std::span<const double> inputs, std::span<const double> modes, MechanismWorkspace* ws) {
  if (!mechanism.exact_stick_elements().empty()) {
    EvaluateMechanism(mechanism, t, x, inputs, modes, ws, {});
  } else {
    EvaluatePositions(mechanism, t, x, ws);
    SetParameterArgs(t, inputs, ws);
  }
}

}  // namespace

bool UpdateElementModes(const Mechanism& mechanism, double t, std::span<double> x, std::span<const double> inputs,
                        std::span<double> modes, MechanismWorkspace* ws) {
  const bool holds = !mechanism.exact_stick_elements().empty();
  bool changed = false;
  // Every pass that changes something releases a hold or settles a slip, so
  // the passes are bounded; the cap is a guard.
  for (int pass = 0; pass <= 2 * mechanism.num_elements(); ++pass) {
    EvaluateForModes(mechanism, t, x, inputs, modes, ws);
    bool changed_now = false;
    for (int e = 0; e < mechanism.num_elements(); ++e) {
      const ForceElement& element = mechanism.element(e);
      if (element.num_modes() == 0) continue;
      const ElementContext ctx = MakeElementContext(mechanism, t, x, modes, *ws, e);
      changed_now |= element.UpdateModes(ctx, x.subspan(mechanism.state_offset(e), element.num_states()),
                                         modes.subspan(mechanism.mode_offset(e), element.num_modes()));
    }
    changed |= changed_now;
    if (!changed_now || !holds) break;
  }
  if (holds) changed |= ZeroStuckVelocities(mechanism, t, x, modes, ws);
  ws->accelerations_valid = false;
  return changed;
}

bool ElementModesAtRest(const Mechanism& mechanism, double t, std::span<double> x, std::span<const double> inputs,
                        std::span<double> modes, MechanismWorkspace* ws) {
  EvaluateForModes(mechanism, t, x, inputs, modes, ws);
  bool changed = false;
  for (int e = 0; e < mechanism.num_elements(); ++e) {
    const ForceElement& element = mechanism.element(e);
    if (element.num_modes() == 0) continue;
    const ElementContext ctx = MakeElementContext(mechanism, t, x, modes, *ws, e);
    changed |= element.ModesAtRest(ctx, x.subspan(mechanism.state_offset(e), element.num_states()),
                                   modes.subspan(mechanism.mode_offset(e), element.num_modes()));
  }
  ws->accelerations_valid = false;
  return changed;
}

Wrench JointReaction(const Mechanism& mechanism, const MechanismWorkspace& ws, int j) {
  const Model& model = mechanism.model();
  const Joint& joint = model.joints()[j];
  Wrench w;
  if (joint.is_cut) {
    const auto& cuts = mechanism.constraints().cut_joints();
    for (int k = 0; k < static_cast<int>(cuts.size()); ++k) {
      if (cuts[k] != j) continue;
      const Constraints::Load load = mechanism.constraints().LoadOf(model, ws.kin, ws.constraint.lambda, k);
      w.force = load.force;
      w.torque = load.torque;
    }
    return w;
  }
  // Force transmitted into the joint's first segment, moved to body 2's
  // attachment point (the end of the joint's chain).
  const int s = joint.first_segment;
  const Pose& pose = ws.kin.pose[s];
  const Vec6& f = ws.dyn.force[s];
  const Pose attach = ws.kin.pose[joint.last_segment] * joint.end_offset;
  w.force = pose.R * f.tail<3>();
  w.torque = pose.R * f.head<3>() - (attach.p - pose.p).cross(w.force);
  return w;
}

}  // namespace mechflow::mech
