#pragma once
// Gearing (ELEMENTS.md 6): gear 1 (centre O1, axis a1) and gear 2 (centre
// O2, axis a2) mesh at the pitch point P, with i = r1/r2 the ratio. P and
// the pitch tangent t come from mech/gear_pitch.h: on the line of centres
// for parallel axes (spur gears), on the contact generatrix of the pitch
// cones for intersecting axes (bevel gears). Which of the two is chosen from
// the axes at the initial configuration; skew axes are an InputError.
// The mesh deflection delta is a state,
// delta' = (v1(P) - v2(P)) . t (material velocities), and the tooth force
//   F = c (delta -+ b/2) + d delta'   beyond the backlash |delta| > b/2,
// never pulling (clipped to the engaged side), acts as -F t on gear 1 and
// +F t on gear 2 at P. The engaged side is a mode switched by events at
// delta = +-b/2. Sensors: force, deflection, mode.

#include "mech/force_element.h"
#include "mech/gear_pitch.h"

namespace mechflow::mech {

struct GearParameters {
  double ratio = 1.0;      // i = r1 / r2 > 0
  double clearance = 0.0;  // b, total backlash along the pitch tangent [m]
  double stiffness = 0.0;  // c [N/m]
  double damping = 0.0;    // d [N s/m]
};

class Gearing final : public ForceElement {
 public:
  // Centres and axes in the frames of their bodies; `initial` is the
  // kinematics of the initial configuration, which decides the kind of axes.
  Gearing(std::string name, std::string origin, int body1, Vec3 centre1, Vec3 axis1, int body2, Vec3 centre2,
          Vec3 axis2, GearParameters parameters, const Kinematics& initial);
  GearAxes axes() const { return axes_; }
  void Initialize(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  void Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                std::span<double> sensors) const override;
  void ZeroCrossings(const ElementContext& ctx, std::span<double> values) const override;
  bool UpdateModes(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  std::string LinearisedAs(std::span<const double> modes) const override;

 private:
  struct Mesh {
    Vec3 p, t;
    double rate;
  };
  Mesh Geometry(const ElementContext& ctx) const;
  double ModeFor(double delta, double rate) const;

  // The pitch geometry at the given kinematics.
  PitchGeometry Pitch(const Kinematics& kin) const;

  int body1_, body2_;
  Vec3 centre1_, axis1_, centre2_, axis2_;
  GearAxes axes_ = GearAxes::kParallel;
  GearParameters p_;
};

}  // namespace mechflow::mech
