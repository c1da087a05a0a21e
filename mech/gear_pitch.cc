#include "mech/gear_pitch.h"

#include <algorithm>
#include <cmath>

namespace mechflow::mech {

GearAxes ClassifyGearAxes(const Vec3& o1, const Vec3& a1, const Vec3& o2, const Vec3& a2, double* gap) {
  const Vec3 normal = a1.cross(a2);
  const double sine = normal.norm();
  if (sine < 1e-9) {
    if (gap) *gap = ((o2 - o1) - (o2 - o1).dot(a1) * a1).norm();
    return GearAxes::kParallel;
  }
  const double distance = std::abs((o2 - o1).dot(normal)) / sine;
  if (gap) *gap = distance;
  return distance <= 1e-6 * (o2 - o1).norm() ? GearAxes::kIntersecting : GearAxes::kSkew;
}

PitchGeometry ParallelPitch(const Vec3& o1, const Vec3& a1, const Vec3& o2, double ratio) {
  PitchGeometry g;
  const Vec3 d = (o2 - o1) - (o2 - o1).dot(a1) * a1;
  const double distance = d.norm();
  if (!(distance > 0)) {
    g.problem = "the gear centres are on one axis";
    return g;
  }
  const Vec3 u = d / distance;
  g.r1 = distance * ratio / (1 + ratio);
  g.p = o1 + g.r1 * u;
  g.t = a1.cross(u);
  return g;
}

PitchGeometry BevelPitch(const Vec3& o1, const Vec3& a1, const Vec3& o2, const Vec3& a2, double ratio) {
  PitchGeometry g;
  // apex: closest points O1 + s a1 and O2 + u a2 of the two lines
  const Vec3 w = o1 - o2;
  const double b = a1.dot(a2), d = a1.dot(w), e = a2.dot(w), denominator = 1 - b * b;
  if (!(denominator > 1e-18)) {
    g.problem = "the axes are parallel (no apex)";
    return g;
  }
  const double s = (b * e - d) / denominator, u = (e - b * d) / denominator;
  const Vec3 apex = 0.5 * ((o1 + s * a1) + (o2 + u * a2));
  const Vec3 to1 = o1 - apex, to2 = o2 - apex;
  const double length1 = to1.norm(), length2 = to2.norm(), scale = (o2 - o1).norm();
  if (!(length1 > 1e-9 * scale) || !(length2 > 1e-9 * scale)) {
    g.problem = "a gear centre is at the apex of the axes (its pitch cone has no size)";
    return g;
  }
  const Vec3 e1 = to1 / length1, e2 = to2 / length2;
  const Vec3 across = e2 - e2.dot(e1) * e1;
  const double sine = across.norm(), cosine = std::clamp(e1.dot(e2), -1.0, 1.0);
  g.shaft_angle = std::atan2(sine, cosine);
  g.cone_angle1 = std::atan2(ratio * sine, 1 + ratio * cosine);
  // a cone of 90 deg or more is a crown or an internal bevel gear: its pitch
  // circle is not at a finite distance from the apex along axis 1
  if (!(g.cone_angle1 < M_PI / 2 - 1e-9)) {
    g.problem = "the pitch cone of gear 1 is flat or inverted (1 + i cos S <= 0); exchange the gears";
    return g;
  }
  const Vec3 n = across / sine;
  g.r1 = length1 * std::tan(g.cone_angle1);
  g.p = o1 + g.r1 * n;
  // a1 is +-e1, so a1 x n is a unit normal to the plane of the axes
  g.t = a1.cross(n);
  return g;
}

}  // namespace mechflow::mech
