#pragma once
// The structure of a sliding model (what makes its analytic Jacobian possible).
//
// A sliding model's segments translate -- joint coordinates and time-driven
// translations -- or are fixed, and the coordinates on any body's path to the
// ground slide along perpendicular axes. No frame turns: each segment's
// rotation is a constant, a body point moves as r0(t) + sum a_i q_i over the
// coordinates i on its path, and the mass matrix M_ij = (a_i . a_j) (the
// mass both carry) is constant and diagonal, M_ii = the mass coordinate i
// carries. Newton's law along a_i then gives each acceleration on its own:
//   M_ii v_i' = tau_i + a_i . sum over the bodies b it carries of
//               (F_b + m_b (g - the time-driven accelerations on b's path))
// (the other coordinates on b's path are perpendicular to a_i).
//
// The model finds its structure once (ModelBuilder); the kinematics, the
// forward dynamics and the analytic Jacobian (mech/sliding_jacobian.h) then
// skip the spatial algebra a turning tree needs.

#include <memory>
#include <string>
#include <vector>

#include "mech/model.h"

namespace mechflow::mech {

struct SlidingStructure {
  // What the kinematics read of a segment and a body, packed: the model's
  // records are large, and a long chain's would not stay in the cache.
  struct Slide {
    int parent, q_index, v_index, signal;
    SegmentDrive drive;
    const TimeFunction* function;
    Vec3 offset;       // the joint frame's origin in the parent's frame
    Vec3 parent_axis;  // the axis in the parent's frame
    Vec3 axis;         // the axis in the segment's frame
  };
  struct Rider {
    int segment;  // kGround: welded to the ground
    Vec3 offset;  // the body frame's origin in the segment's frame
    Vec3 turned;  // the same turned into global axes (constant: segments only translate)
  };
  std::vector<Slide> slides;  // per segment
  std::vector<Rider> riders;  // per body
  std::vector<Mat3> rotation;           // per segment: its frame's constant global rotation
  std::vector<Vec3> axis;               // per segment: global unit axis of its translation (zero: fixed)
  std::vector<double> carried_mass;     // per segment: the mass of the bodies riding on it
  std::vector<double> coordinate_mass;  // per velocity coordinate: M_ii
  // Per body, the segments of the coordinates on its path to the ground:
  // path_segments[path_start[b] .. path_start[b + 1]).
  std::vector<int> path_start, path_segments;
};

// The model's sliding structure, or null with *why saying, as a sentence
// naming the joint, why the model is not a sliding one.
std::shared_ptr<const SlidingStructure> FindSlidingStructure(const Model& model, std::string* why);

}  // namespace mechflow::mech
