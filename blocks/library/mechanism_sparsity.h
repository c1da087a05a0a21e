#pragma once
// The structural sparsity of a mechanism block (blocks/framework/block.h,
// BlockSparsity), derived from the mechanism's topology.
//
// Groups: every segment tree hanging from the ground is one group, and trees
// joined by a constraint (a loop-closing or constant-velocity joint, with its
// ghost chain) form one group. Then:
//   - q' of a segment reads that segment's v (and, for a free segment, its
//     q too: the quaternion turns body-axis velocities into rates);
//   - v' of a group reads the q and v of the group (the articulated-body
//     pass couples a whole tree, the constraint solve a whole group) and,
//     for every element acting on a body or coordinate of the group, the q
//     and v of all groups the element touches and the element's states;
//   - an element's state rates read the same as the element's loads;
//   - inputs reach the v' of the groups touched by elements whose
//     parameters follow inputs, and those elements' states.
// Sensors: positions, velocities and angles read their body's group;
// element sensors what the element reads; accelerations and reactions what
// the v' of their groups read.
//
// Conservative: an element that does not declare what it touches
// (ForceElement::declares_footprint) makes the whole pattern dense, and so
// does a coordinate that no segment owns.

#include <optional>
#include <vector>

#include "blocks/framework/block.h"
#include "mech/sensor.h"

namespace mechflow::blocks {

// The block's sparsity, or nothing when only the dense default is safe.
std::optional<BlockSparsity> MechanismSparsity(const mech::Mechanism& mechanism,
                                               const std::vector<mech::SensorSpec>& sensors);

}  // namespace mechflow::blocks
