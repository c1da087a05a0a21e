#pragma once
// Gearing (ELEMENTS.md 6), parallel axes: gear 1 (centre O1, axis a1) and
// gear 2 (centre O2) mesh at the pitch point P on the line of centres,
//   u = unit(O2 - O1, a1 component removed), A = its length,
//   r1 = A i / (1 + i), r2 = A / (1 + i), P = O1 + r1 u, t = a1 x u,
// with i = r1/r2 the ratio. The mesh deflection delta is a state,
// delta' = (v1(P) - v2(P)) . t (material velocities), and the tooth force
//   F = c (delta -+ b/2) + d delta'   beyond the backlash |delta| > b/2,
// never pulling (clipped to the engaged side), acts as -F t on gear 1 and
// +F t on gear 2 at P. The engaged side is a mode switched by events at
// delta = +-b/2. Sensors: force, deflection, mode.

#include "mech/force_element.h"

namespace mechflow::mech {

struct GearParameters {
  double ratio = 1.0;      // i = r1 / r2 > 0
  double clearance = 0.0;  // b, total backlash along the pitch tangent [m]
  double stiffness = 0.0;  // c [N/m]
  double damping = 0.0;    // d [N s/m]
};

class Gearing final : public ForceElement {
 public:
  Gearing(std::string name, std::string origin, int body1, Vec3 centre1, Vec3 axis1, int body2, Vec3 centre2,
          GearParameters parameters);
  void Initialize(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  void Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                std::span<double> sensors) const override;
  void ZeroCrossings(const ElementContext& ctx, std::span<double> values) const override;
  bool UpdateModes(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;

 private:
  struct Mesh {
    Vec3 p, t;
    double rate;
  };
  Mesh Geometry(const ElementContext& ctx) const;
  double ModeFor(double delta, double rate) const;

  int body1_, body2_;
  Vec3 centre1_, axis1_, centre2_;
  GearParameters p_;
};

}  // namespace mechflow::mech
