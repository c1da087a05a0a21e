#include "blocks/library/mechanism_sparsity.h"

#include <algorithm>
#include <numeric>

namespace mechflow::blocks {
namespace {

using IndexSet = std::vector<int>;

void Add(const IndexSet& from, IndexSet* into) { into->insert(into->end(), from.begin(), from.end()); }

void Normalize(IndexSet* s) {
  std::sort(s->begin(), s->end());
  s->erase(std::unique(s->begin(), s->end()), s->end());
}

// Union-find over segment trees.
struct Groups {
  explicit Groups(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int Find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void Join(int a, int b) { parent[Find(a)] = Find(b); }
  std::vector<int> parent;
};

}  // namespace

std::optional<BlockSparsity> MechanismSparsity(const mech::Mechanism& m,
                                               const std::vector<mech::SensorSpec>& sensors) {
  const mech::Model& model = m.model();
  const int nq = model.nq(), nv = model.nv(), num_segments = static_cast<int>(model.segments().size());
  for (int e = 0; e < m.num_elements(); ++e)
    if (!m.element(e).declares_footprint()) return std::nullopt;
  if (m.drive_work_state() >= 0) return std::nullopt;  // its rate reads every acceleration

  // the root segment of every segment, then groups of roots joined by loops
  // (parents come before their children: one pass, where walking each
  // segment's path was quadratic in a serial chain)
  std::vector<int> root(num_segments);
  for (int s = 0; s < num_segments; ++s) {
    const int parent = model.segments()[s].parent;
    root[s] = parent == mech::kGround ? s : root[parent];
  }
  Groups groups(num_segments);
  auto segment_of_body = [&](int body) { return model.bodies()[body].segment; };
  std::vector<std::vector<int>> joint_segments(model.joints().size());  // (one pass: not one per loop)
  for (int s = 0; s < num_segments; ++s)
    if (const int j = model.segments()[s].joint; j >= 0) joint_segments[j].push_back(s);
  for (int j = 0; j < static_cast<int>(model.joints().size()); ++j) {
    const mech::Joint& joint = model.joints()[j];
    if (!joint.is_cut && !joint.convel) continue;
    std::vector<int> members;
    for (const int body : {joint.body1, joint.body2})
      if (segment_of_body(body) != mech::kGround) members.push_back(root[segment_of_body(body)]);
    for (const int s : joint_segments[j]) members.push_back(root[s]);
    for (std::size_t k = 1; k < members.size(); ++k) groups.Join(members[k], members[0]);
  }
  auto group_of_segment = [&](int s) { return groups.Find(root[s]); };

  // coordinates of each segment and of each group
  std::vector<int> q_owner(nq, -1), v_owner(nv, -1);
  for (int s = 0; s < num_segments; ++s) {
    const mech::Segment& seg = model.segments()[s];
    if (seg.drive != mech::SegmentDrive::kDof) continue;
    const bool free = seg.motion == mech::SegmentMotion::kFree;
    for (int k = 0; k < (free ? 7 : 1); ++k) q_owner[seg.q_index + k] = s;
    for (int k = 0; k < (free ? 6 : 1); ++k) v_owner[seg.v_index + k] = s;
  }
  if (std::count(q_owner.begin(), q_owner.end(), -1) > 0 || std::count(v_owner.begin(), v_owner.end(), -1) > 0)
    return std::nullopt;
  std::vector<IndexSet> group_coordinates(num_segments);  // by group id: its q and v states
  for (int i = 0; i < nq; ++i) group_coordinates[group_of_segment(q_owner[i])].push_back(i);
  for (int i = 0; i < nv; ++i) group_coordinates[group_of_segment(v_owner[i])].push_back(nq + i);

  // the groups each element touches
  std::vector<IndexSet> element_groups(m.num_elements());
  for (int e = 0; e < m.num_elements(); ++e) {
    const mech::ForceElement& element = m.element(e);
    IndexSet& g = element_groups[e];
    for (const int body : element.bodies())
      if (segment_of_body(body) != mech::kGround) g.push_back(group_of_segment(segment_of_body(body)));
    for (const int v : element.coordinates()) g.push_back(group_of_segment(v_owner[v]));
    Normalize(&g);
  }
  const auto element_states = [&](int e, IndexSet* into) {
    for (int k = 0; k < m.element(e).num_states(); ++k) into->push_back(m.state_offset(e) + k);
  };
  // what an element reads: the coordinates of its groups and its states
  // (built where needed: one copy per element would be quadratic in a chain)
  const auto element_reads = [&](int e) {
    IndexSet reads;
    for (const int group : element_groups[e]) Add(group_coordinates[group], &reads);
    element_states(e, &reads);
    Normalize(&reads);
    return reads;
  };

  // What the accelerations of each group read: the coordinates of every
  // group its elements touch, and those elements' states; and whether
  // inputs reach them. Groups are gathered first, so each group's
  // coordinates are added once however many elements share them.
  std::vector<IndexSet> group_reads(num_segments), touched(num_segments);
  std::vector<bool> group_inputs(num_segments, false);
  for (int g = 0; g < num_segments; ++g) touched[g].push_back(g);
  for (int e = 0; e < m.num_elements(); ++e)
    for (const int g : element_groups[e]) {
      Add(element_groups[e], &touched[g]);
      element_states(e, &group_reads[g]);
      if (m.element(e).depends_on_inputs()) group_inputs[g] = true;
    }
  for (int g = 0; g < num_segments; ++g) {
    Normalize(&touched[g]);
    for (const int h : touched[g]) Add(group_coordinates[h], &group_reads[g]);
    Normalize(&group_reads[g]);
  }

  // the scalar inputs, then one port per driving signal; a drive moves
  // bodies that any element may touch, so it reaches everything (a superset)
  const bool driven = !model.drive_signals().empty();
  IndexSet all_inputs(m.num_inputs() + model.drive_signals().size());
  std::iota(all_inputs.begin(), all_inputs.end(), 0);
  if (driven) std::fill(group_inputs.begin(), group_inputs.end(), true);
  BlockSparsity out;
  out.derivative_states.resize(m.num_states());
  out.derivative_inputs.resize(m.num_states());
  // q' from the segment's own coordinates
  for (int i = 0; i < nq; ++i) {
    const int s = q_owner[i];
    const mech::Segment& seg = model.segments()[s];
    const bool free = seg.motion == mech::SegmentMotion::kFree;
    IndexSet& row = out.derivative_states[i];
    for (int k = 0; k < (free ? 6 : 1); ++k) row.push_back(nq + seg.v_index + k);
    if (free)
      for (int k = 0; k < 7; ++k) row.push_back(seg.q_index + k);
    if (!model.has_quaternions()) row.push_back(nq + i);  // CoordinateRates copies v[i] then
    Normalize(&row);
  }
  for (int i = 0; i < nv; ++i) {
    const int g = group_of_segment(v_owner[i]);
    out.derivative_states[nq + i] = group_reads[g];
    if (group_inputs[g]) out.derivative_inputs[nq + i] = all_inputs;
  }
  for (int e = 0; e < m.num_elements(); ++e)
    for (int k = 0; k < m.element(e).num_states(); ++k) {
      out.derivative_states[m.state_offset(e) + k] = element_reads(e);
      if (driven || m.element(e).depends_on_inputs()) out.derivative_inputs[m.state_offset(e) + k] = all_inputs;
    }

  // sensors
  auto body_group_coordinates = [&](int body, IndexSet* into) {
    if (segment_of_body(body) != mech::kGround) Add(group_coordinates[group_of_segment(segment_of_body(body))], into);
  };
  auto body_group_reads = [&](int body, IndexSet* into) {
    if (segment_of_body(body) != mech::kGround) Add(group_reads[group_of_segment(segment_of_body(body))], into);
  };
  IndexSet everything(m.num_states());
  std::iota(everything.begin(), everything.end(), 0);
  for (const mech::SensorSpec& sensor : sensors) {
    IndexSet row;
    switch (sensor.kind) {
      case mech::SensorKind::kCoordinate:
      case mech::SensorKind::kVelocity:
      case mech::SensorKind::kAcceleration: {
        const int v = model.dofs()[sensor.index].v_index;
        if (v < 0) row = everything;
        else if (sensor.kind == mech::SensorKind::kAcceleration) Add(group_reads[group_of_segment(v_owner[v])], &row);
        else Add(group_coordinates[group_of_segment(v_owner[v])], &row);
        break;
      }
      case mech::SensorKind::kPointPosition:
      case mech::SensorKind::kPointVelocity:
      case mech::SensorKind::kBodyAngles:
      case mech::SensorKind::kBodyAngularVelocity:
        body_group_coordinates(sensor.index, &row);
        break;
      case mech::SensorKind::kPointAcceleration:
        body_group_reads(sensor.index, &row);
        break;
      case mech::SensorKind::kReactionForce:
      case mech::SensorKind::kReactionTorque:
        body_group_reads(model.joints()[sensor.index].body1, &row);
        body_group_reads(model.joints()[sensor.index].body2, &row);
        break;
      case mech::SensorKind::kElement:
        row = element_reads(sensor.index);
        break;
      default:
        row = everything;  // a kind added later: the safe answer
    }
    Normalize(&row);
    out.output_states.push_back(std::move(row));
  }
  return out;
}

}  // namespace mechflow::blocks
