#pragma once
// The `basic` traversal, the seed's baseline: one thread per query runs the whole query
// (detail::query_collides: kinematics, broad phase, then each surviving body's BVTT
// depth-first on a private stack).

#include <cstdint>

#include "traversals/traversal_common.cuh"

namespace gplanner::traversals {

// d_q: device, shape [n, m.width]; d_verdicts: device, shape [n] (1: collision).
void run_basic(const CollisionModelView& m, const float* d_q, int n, std::uint8_t* d_verdicts,
               DeviceTestCounts* d_counts);

}  // namespace gplanner::traversals
