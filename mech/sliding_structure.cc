#include "mech/sliding_structure.h"

#include <cmath>

namespace mechflow::mech {

std::shared_ptr<const SlidingStructure> FindSlidingStructure(const Model& model, std::string* why) {
  const auto& segments = model.segments();
  auto s = std::make_shared<SlidingStructure>();
  s->rotation.resize(segments.size());
  s->axis.assign(segments.size(), Vec3::Zero());
  s->carried_mass.assign(segments.size(), 0.0);
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment& seg = segments[i];
    if (seg.drive != SegmentDrive::kNone && seg.motion != SegmentMotion::kPrismatic) {
      *why = "joint '" + model.joints()[seg.joint].name + "' turns (only translations keep the mass matrix constant)";
      return nullptr;
    }
    // segments come after their parents
    s->rotation[i] = (seg.parent == kGround ? Mat3::Identity() : s->rotation[seg.parent]) * seg.placement.R;
    if (seg.drive != SegmentDrive::kNone) s->axis[i] = s->rotation[i] * seg.axis;
    const Vec3 axis = seg.drive == SegmentDrive::kNone ? Vec3::Zero() : seg.axis;
    s->slides.push_back({seg.parent, seg.q_index, seg.v_index, seg.signal, seg.drive, seg.function.get(),
                         seg.placement.p, seg.placement.R * axis, axis});
  }
  for (const Body& body : model.bodies()) {
    const Vec3& offset = body.in_segment.p;
    s->riders.push_back({body.segment, offset, body.segment == kGround ? offset : s->rotation[body.segment] * offset});
  }
  s->coordinate_mass.assign(model.nv(), 0.0);
  for (const Body& body : model.bodies()) {
    if (body.segment != kGround) s->carried_mass[body.segment] += body.mass;
    s->path_start.push_back(static_cast<int>(s->path_segments.size()));
    for (int i = body.segment; i != kGround; i = segments[i].parent) {
      if (segments[i].drive != SegmentDrive::kDof) continue;
      for (int k = s->path_start.back(); k < static_cast<int>(s->path_segments.size()); ++k) {
        const int below = s->path_segments[k];
        if (std::abs(s->axis[i].dot(s->axis[below])) > 1e-12) {
          *why = "joint '" + model.joints()[segments[below].joint].name +
                 "' slides along a direction not perpendicular to one of joint '" +
                 model.joints()[segments[i].joint].name + "' it rides on (the mass matrix is not diagonal)";
          return nullptr;
        }
      }
      s->path_segments.push_back(i);
      s->coordinate_mass[segments[i].v_index] += body.mass;
    }
  }
  s->path_start.push_back(static_cast<int>(s->path_segments.size()));
  for (const Segment& seg : segments)
    if (seg.drive == SegmentDrive::kDof && !(s->coordinate_mass[seg.v_index] > 0.0)) {
      *why = "joint '" + model.joints()[seg.joint].name + "' carries no mass";
      return nullptr;
    }
  why->clear();
  return s;
}

}  // namespace mechflow::mech
