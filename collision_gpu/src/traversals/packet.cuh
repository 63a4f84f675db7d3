#pragma once
// The `packet` traversal: queries clustered by k-means on their configurations (so that
// a packet's queries take similar poses), cut into warp-sized packets in cluster order;
// a warp walks each body's BVTT for its 32 queries together on one shared stack,
// visiting first the child pair that more of its queries overlap (the seed's greedy
// collision-probability order).

#include <cstdint>

#include "traversals/traversal_common.cuh"

namespace gplanner::traversals {

class PacketTraversal {
 public:
  // d_q: device, shape [n, m.width]; d_verdicts: device, shape [n] (1: collision).
  void run(const CollisionModelView& m, const float* d_q, int n, std::uint8_t* d_verdicts,
           DeviceTestCounts* d_counts);

 private:
  // d_order (shape [n]): the queries sorted by their cluster.
  void cluster(const float* d_q, int n, int width);

  cuda::DeviceBuffer<unsigned> labels_, sorted_labels_, order_, identity_;
  cuda::DeviceBuffer<float> centres_, sums_;
  cuda::DeviceBuffer<unsigned> cluster_counts_;
  cuda::DeviceBuffer<unsigned char> sort_scratch_;
};

}  // namespace gplanner::traversals
