#pragma once
// ForceElement: anything that applies loads to a mechanism from its state:
// springs, dampers, bushings, joint forces, and (later) friction elements and
// contacts with memory.
//
// An element declares, in its constructor, its sensor outputs ("force",
// "length", "rate", ...), and -- for elements with memory -- continuous
// internal states (integrated with the mechanism), discrete modes (stick/
// slip, contact open/closed) and zero-crossing functions whose sign change is
// the event that switches a mode. Mode switches are never `if`s hidden inside
// a step: Evaluate() uses the current mode; OnCrossing() changes it.
//
// Run-time methods are const, must not allocate, and report bad numbers by
// throwing SimulationError.

#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "mech/loads.h"
#include "mech/time_function.h"

namespace mechflow::mech {

enum class Crossing { kRising, kFalling, kEither };

// An element's own scratch for a run's evaluations (ForceElement::MakeScratch):
// what it measured on the current kinematics, kept for the many calls of one
// evaluation (the exact-stick solve asks a contact about its points dozens of
// times). Owned by the mechanism's workspace, one per element.
struct ElementScratch {
  virtual ~ElementScratch() = default;
};

// Everything an element may read during one evaluation.
struct ElementContext {
  double t = 0.0;
  const Model* model = nullptr;
  const Kinematics* kin = nullptr;
  std::span<const double> q, v;
  // [t, input_0, input_1, ...]: the arguments of parameters that depend on
  // the mechanism's inputs (see Parameter).
  std::span<const double> parameter_args;
  std::span<const double> state;  // this element's continuous states
  std::span<const double> modes;  // this element's discrete modes
  // An exact-stick element's holding forces, one per hold (see
  // ForceElement::StuckExactly): the solved force of a stuck hold, 0 for
  // the others. Empty for an element without holds.
  std::span<const double> stick_forces;
  // ZeroCrossings only: this element's sensors, when Evaluate computed them
  // on the same kinematics; empty otherwise.
  std::span<const double> sensors;
  // This element's scratch (MakeScratch); null for an element that makes none.
  ElementScratch* scratch = nullptr;
};

class DynamicsWorkspace;

// Partial derivatives of an element's force along its coordinate
// (Coordinate(""), kind kLine or kJoint) and of its state rates, in the
// current modes, for an analytic Jacobian (mech/sliding_jacobian.h): x and v
// are the coordinate and its rate, s_k the element's own states.
struct ElementDerivatives {
  static constexpr int kMaxStates = 2;
  double force_x = 0.0, force_v = 0.0;
  std::array<double, kMaxStates> force_s{};
  std::array<double, kMaxStates> rate_x{}, rate_v{};               // d s_k' / dx, d s_k' / dv
  std::array<std::array<double, kMaxStates>, kMaxStates> rate_s{};  // d s_k' / d s_m
};

// What an element tells an analytic Jacobian.
enum class DerivativeSupport {
  kNone,              // nothing: the solver takes difference quotients
  kStateIndependent,  // its loads depend on time and inputs alone (a given force on a body that
                      // cannot turn: in a sliding mechanism, where no body turns)
  kAlongCoordinate,   // ForceElement::Derivatives
};

// The scalar coordinate an element acts along, for driving the element alone
// (force analysis, analysis/force_analysis.h):
//   kLine         the length between point1 on body 1 and point2 on body 2
//   kJoint        a joint coordinate (q_index, v_index)
//   kPenetration  of body 1's points into the plane on body 2 with normal
//                 `axis` (body 2's frame): moving body 1 along -normal
//                 deepens it
//   kTranslation  of body 2's point2 from body 1's point1 along `axis`
//                 (body 1's frame)
//   kRotation     of body 2 about `axis` (body 1's frame) through point2
// `force_sensor` times `force_sign` is the element's force (or moment) along
// the coordinate: positive pushes the coordinate up; `coordinate_sensor`
// reads the coordinate.
struct ElementCoordinate {
  enum class Kind { kNone, kLine, kJoint, kPenetration, kTranslation, kRotation };
  Kind kind = Kind::kNone;
  int body1 = -1, body2 = -1;
  Vec3 point1 = Vec3::Zero(), point2 = Vec3::Zero();  // body frames
  Vec3 axis = Vec3::Zero();
  int q_index = -1, v_index = -1;
  int force_sensor = 0;
  double force_sign = 1.0;
  int coordinate_sensor = 1;  // "length" of lines and joint forces, a contact's "penetration"

  static ElementCoordinate Line(int body1, const Vec3& point1, int body2, const Vec3& point2) {
    ElementCoordinate c;
    c.kind = Kind::kLine;
    c.body1 = body1, c.body2 = body2, c.point1 = point1, c.point2 = point2;
    return c;
  }
  static ElementCoordinate Joint(int q_index, int v_index) {
    ElementCoordinate c;
    c.kind = Kind::kJoint;
    c.q_index = q_index, c.v_index = v_index;
    return c;
  }
  // a contact: its sensor 0 ("normal") pushes the penetration down
  static ElementCoordinate Penetration(int body1, int body2, const Vec3& normal) {
    ElementCoordinate c;
    c.kind = Kind::kPenetration;
    c.body1 = body1, c.body2 = body2, c.axis = normal;
    c.force_sign = -1.0;
    return c;
  }
};

// A numeric element parameter: a constant, or a function of (t, inputs...)
// when it is an expression of identifiers that are mechanism inputs.
struct Parameter {
  double value = 0.0;
  std::shared_ptr<const ScalarFunction> function;
  bool uses_inputs = false;  // the function reads inputs (not just t)

  Parameter() = default;
  Parameter(double v) : value(v) {}  // NOLINT: a constant reads naturally
  double Get(const ElementContext& ctx) const { return function ? function->Evaluate(ctx.parameter_args) : value; }
  bool is_constant() const { return !function; }
};

class ForceElement {
 public:
  ForceElement(std::string name, std::string origin) : name_(std::move(name)), origin_(std::move(origin)) {}
  virtual ~ForceElement() = default;
  ForceElement(const ForceElement&) = delete;
  ForceElement& operator=(const ForceElement&) = delete;

  // The scratch a workspace keeps for this element (ElementContext::scratch),
  // made once per workspace so that evaluations allocate nothing.
  virtual std::unique_ptr<ElementScratch> MakeScratch() const { return nullptr; }

  const std::string& name() const { return name_; }
  const std::string& origin() const { return origin_; }
  const std::vector<std::string>& sensor_names() const { return sensors_; }
  int num_sensors() const { return static_cast<int>(sensors_.size()); }
  int FindSensor(const std::string& sensor) const {
    for (int i = 0; i < num_sensors(); ++i)
      if (sensors_[i] == sensor) return i;
    return -1;
  }
  // True when the element's loads and sensors depend on the mechanism's
  // inputs at the same instant (a parameter follows an input); its sensors
  // then feed through from the inputs.
  bool depends_on_inputs() const { return depends_on_inputs_; }
  // What the element reads and loads, for sparse Jacobians: the bodies
  // (Base0 included) whose motion it reads and on which it acts, and the
  // velocity coordinates (v indices) it reads and loads directly. Both empty:
  // not declared, read as "every body and coordinate".
  const std::vector<int>& bodies() const { return bodies_; }
  const std::vector<int>& coordinates() const { return coordinates_; }
  bool declares_footprint() const { return !exact_stick() && (!bodies_.empty() || !coordinates_.empty()); }
  int num_states() const { return num_states_; }
  int num_modes() const { return num_modes_; }
  int num_crossings() const { return static_cast<int>(crossings_.size()); }
  Crossing crossing_direction(int i) const { return crossings_.at(i); }

  // Initial internal states and modes from the initial configuration.
  virtual void Initialize(const ElementContext&, std::span<double> /*state*/, std::span<double> /*modes*/) const {}
  // Adds the element's loads, writes the rates of its internal states and its
  // sensor values.
  virtual void Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                        std::span<double> sensors) const = 0;
  virtual void ZeroCrossings(const ElementContext&, std::span<double> /*values*/) const {}
  // Crossing `index` fired (direction +1 rising, -1 falling): switch modes,
  // reset internal states.
  virtual void OnCrossing(int /*index*/, int /*direction*/, const ElementContext&, std::span<double> /*state*/,
                          std::span<double> /*modes*/) const {}
  // After initialisation and every event: make the modes agree with the
  // current state (e.g. a slip direction the velocity contradicts). Returns
  // true when a mode changed.
  virtual bool UpdateModes(const ElementContext&, std::span<double> /*state*/, std::span<double> /*modes*/) const {
    return false;
  }
  // After every step the integrator takes: an element whose modes record a
  // direction of slip turns it to the slip of that state (a contact point's,
  // mech/contact_stick.h), so that the end of a slip is a reversal within
  // one step, not a turn of the slip's direction.
  virtual void FollowSlip(const ElementContext&, std::span<double> /*modes*/) const {}
  // A static equilibrium search (analysis/linearization.h) at a candidate state
  // at rest: set the modes that element takes there -- a contact's from its
  // penetration, a sliding friction element sticks, a stuck one beyond its
  // static limit breaks away. Returns true when a mode (or a state it resets)
  // changed. By default UpdateModes, right for modes the state decides.
  virtual bool ModesAtRest(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const {
    return UpdateModes(ctx, state, modes);
  }
  // Exact stick (docs/ELEMENTS.md 3.6). An element that declared holds
  // (DeclareExactStick) -- one relative motion each: a friction element's
  // slide, the two tangential slips of a contact point -- and reports a hold
  // StuckExactly keeps that motion's acceleration at zero by a constraint
  // force: the mechanism finds the forces f that keep the stuck holds'
  // accelerations (StickAcceleration, affine in f) at zero and passes them
  // in ElementContext::stick_forces; Evaluate applies them through
  // ApplyStickForce and the element's crossings compare them with its
  // static limits. The modes decide which holds stick, nothing else.
  bool exact_stick() const { return num_holds_ > 0; }
  int num_holds() const { return num_holds_; }
  virtual bool StuckExactly(const ElementContext&, int /*hold*/) const { return false; }
  // Adds the loads of holding force f on `hold` (the element's own sign convention).
  virtual void ApplyStickForce(const ElementContext&, int /*hold*/, double /*f*/, Loads*) const {}
  // The hold's relative acceleration after a dynamics pass (accelerations
  // in `dyn`, generalized ones in `vdot`): the rate of HoldVelocity.
  virtual double StickAcceleration(const ElementContext&, int /*hold*/, const DynamicsWorkspace& /*dyn*/,
                                   std::span<const double> /*vdot*/) const {
    return 0.0;
  }
  // The relative velocity the hold keeps at zero (a stuck hold starts with
  // the root finder's residual, which the mechanism removes at events).
  virtual double HoldVelocity(const ElementContext&, int /*hold*/) const { return 0.0; }
  // What to call a hold in a message: "contact 'c'".
  virtual std::string HoldName(int /*hold*/) const { return "element '" + name() + "'"; }
  // A stuck hold that no force moves while the mechanism drives it
  // (SolveHoldingForces): an error for a contact (a point of a driven body
  // cannot be held, and a regularised stick says what happens), left
  // without a holding force for a friction element on a coordinate, which
  // meets it in passing where a loop's dead centre stops the coordinate.
  virtual bool UnholdableIsError() const { return false; }
  // Work accounting (for the energy balance of a run), switched on before the mechanism is
  // built when a sensor asks for it: one more state, the work W the element
  // has done on the bodies (the mechanism integrates the power of its
  // loads), and the sensors "work" and -- for an element whose sensor
  // "energy" gives its stored elastic energy U -- "dissipated" = U(0) - U - W.
  void TrackWork() {
    if (tracks_work()) return;
    work_state_ = num_states_;
    DeclareStates(1);
    work_sensor_ = num_sensors();
    DeclareSensor("work");
    if (stores_energy()) DeclareSensor("dissipated");
  }
  bool tracks_work() const { return work_state_ >= 0; }
  int work_state() const { return work_state_; }    // among the element's states
  int work_sensor() const { return work_sensor_; }  // "dissipated" follows when stores_energy()
  bool stores_energy() const { return energy_sensor_ >= 0; }
  int energy_sensor() const { return energy_sensor_; }

  // Analytic Jacobian (mech/sliding_jacobian.h): what the element can tell,
  // fixed at construction, and -- for kAlongCoordinate -- its derivatives at
  // the coordinate's value x and rate v. Parameters that follow inputs count
  // as constants (the inputs are held).
  virtual DerivativeSupport derivative_support() const { return DerivativeSupport::kNone; }
  virtual void Derivatives(const ElementContext&, double /*x*/, double /*v*/, ElementDerivatives*) const {}

  // The element's scalar coordinate (kind kNone: it has none, e.g. an
  // applied force). `component` names one of several (a bushing's); empty
  // for the element's own.
  virtual ElementCoordinate Coordinate(const std::string& /*component*/) const { return {}; }

  // What crossing `index` firing in `direction` means, for the event log
  // (`mechflow run --verbose`): "sticks", "breaks away forward", ...
  virtual std::string CrossingName(int index, int /*direction*/) const {
    return "crossing " + std::to_string(index);
  }

  // How the element enters a linearisation in these modes (its slice), for
  // `mechflow modes`: "stuck, held exactly: ...". Empty for elements
  // without modes.
  virtual std::string LinearisedAs(std::span<const double> /*modes*/) const { return ""; }

  // Crossing `index` fired in `direction`: a warning for the user when the
  // event means "check the model" (e.g. a contact sinking deeper than its
  // bound), else empty. Called after a run, not at run time.
  virtual std::string CrossingWarning(int /*index*/, int /*direction*/) const { return ""; }

  // At the assembled initial state: a warning for the user when the element
  // starts where a CrossingWarning would have fired had it got there (a
  // contact already deeper than its bound never crosses it), else empty.
  // The loader prints it with the element's origin.
  virtual std::string StartWarning(const ElementContext&) const { return ""; }

 protected:
  // "energy" is the stored elastic energy (see TrackWork).
  void DeclareSensor(std::string sensor) {
    if (sensor == "energy") energy_sensor_ = num_sensors();
    sensors_.push_back(std::move(sensor));
  }
  void DeclareStates(int n) { num_states_ += n; }
  void DeclareDependsOnInputs(bool depends) { depends_on_inputs_ = depends_on_inputs_ || depends; }
  // Its holding force follows from the whole mechanism's balance: its
  // sensors then depend on the inputs, and it touches every body (the
  // Jacobian's pattern is dense).
  void DeclareExactStick(int holds = 1) {
    num_holds_ = holds;
    depends_on_inputs_ = true;
  }
  void DeclareModes(int n) { num_modes_ += n; }
  void DeclareBodies(std::vector<int> bodies) { bodies_ = std::move(bodies); }
  void DeclareCoordinates(std::vector<int> v_indices) { coordinates_ = std::move(v_indices); }
  int DeclareCrossing(Crossing direction) {
    crossings_.push_back(direction);
    return num_crossings() - 1;
  }

 private:
  std::string name_, origin_;
  std::vector<std::string> sensors_;
  int num_states_ = 0, num_modes_ = 0;
  bool depends_on_inputs_ = false;
  int num_holds_ = 0;
  int work_state_ = -1, work_sensor_ = -1, energy_sensor_ = -1;
  std::vector<Crossing> crossings_;
  std::vector<int> bodies_, coordinates_;
};

}  // namespace mechflow::mech
