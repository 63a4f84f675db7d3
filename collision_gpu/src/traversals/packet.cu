#include "traversals/packet.cuh"

#include <algorithm>
#include <cub/device/device_radix_sort.cuh>

namespace gplanner::traversals {
namespace {

// k-means on configurations: assign every query to its nearest centre.
__global__ void kmeans_assign_kernel(const float* d_q, int n, int width, const float* d_centres,
                                     int k, unsigned* d_labels) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const float* q = d_q + static_cast<std::size_t>(i) * width;
  float best = 3.4e38f;
  unsigned label = 0;
  for (int c = 0; c < k; ++c) {
    float d2 = 0;
    for (int j = 0; j < width; ++j) {
      const float d = q[j] - d_centres[c * width + j];
      d2 += d * d;
    }
    if (d2 < best) {
      best = d2;
      label = c;
    }
  }
  d_labels[i] = label;
}

__global__ void kmeans_accumulate_kernel(const float* d_q, int n, int width,
                                         const unsigned* d_labels, float* d_sums,
                                         unsigned* d_counts) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const unsigned c = d_labels[i];
  for (int j = 0; j < width; ++j)
    atomicAdd(&d_sums[c * width + j], d_q[static_cast<std::size_t>(i) * width + j]);
  atomicAdd(&d_counts[c], 1u);
}

__global__ void kmeans_update_kernel(float* d_centres, const float* d_sums,
                                     const unsigned* d_counts, int k, int width) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= k * width) return;
  const unsigned count = d_counts[t / width];
  if (count > 0) d_centres[t] = d_sums[t] / count;  // an empty cluster keeps its centre
}

__global__ void kmeans_init_kernel(const float* d_q, int n, int width, float* d_centres, int k) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= k * width) return;
  const int c = t / width, j = t % width;
  const std::size_t sample = static_cast<std::size_t>(c) * n / k;  // evenly spread seeds
  d_centres[t] = d_q[sample * width + j];
}

__global__ void iota_kernel(unsigned* d_values, int n) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) d_values[i] = i;
}

constexpr int kPacketWarpsPerBlock = 4;

struct PacketEntry {
  int a, b;
  unsigned mask;  // lanes whose queries overlap this node pair
};

// One warp walks the BVTT of bodies A and B for its 32 queries together, on one shared
// stack, each entry carrying the lanes that overlap it. Children are tested when their
// parent is expanded; the pair more lanes overlap is visited first.
__device__ void packet_traverse(const CollisionModelView& m, BodyRange a, BodyRange b,
                                const detail::Xf& X_AB, detail::BodyTolerance tolerance,
                                unsigned active, PacketEntry* stack, bool* collided,
                                detail::TraversalCounts* counts) {
  const unsigned lane = threadIdx.x & 31;
  const bool mine = (active >> lane) & 1u;
  auto overlaps = [&](int ia, int ib) {
    if (counts) ++counts->bv_tests;
    return detail::nodes_overlap(m.nodes[a.node_offset + ia], m.nodes[b.node_offset + ib], X_AB,
                                 tolerance.margin);
  };
  const unsigned root = __ballot_sync(kFullMask, mine && overlaps(0, 0));
  if (root == 0) return;
  int top = 0;
  if (lane == 0) stack[0] = {0, 0, root};
  top = 1;
  __syncwarp();
  while (top > 0) {
    --top;
    const PacketEntry entry = stack[top];
    __syncwarp();
    const unsigned done = __ballot_sync(kFullMask, *collided);
    const unsigned mask = entry.mask & ~done;
    if (mask == 0) continue;
    const bool in = (mask >> lane) & 1u;
    const BvhNode& na = m.nodes[a.node_offset + entry.a];
    const BvhNode& nb = m.nodes[b.node_offset + entry.b];
    if (na.is_leaf() && nb.is_leaf()) {
      if (in) {
        if (counts) ++counts->triangle_tests;
        if (detail::leaf_collides(m.triangles[a.triangle_offset + na.triangle()],
                                  m.triangles[b.triangle_offset + nb.triangle()], X_AB,
                                  tolerance.threshold)) {
          *collided = true;
        }
      }
      continue;
    }
    detail::NodePair p0, p1;
    detail::split_node_pair(entry.a, entry.b, na, nb, &p0, &p1);
    const unsigned m0 = __ballot_sync(kFullMask, in && overlaps(p0.a, p0.b));
    const unsigned m1 = __ballot_sync(kFullMask, in && overlaps(p1.a, p1.b));
    // Push the less popular pair first so that the more popular one is popped next.
    const bool first_more = __popc(m0) >= __popc(m1);
    const PacketEntry later{first_more ? p1.a : p0.a, first_more ? p1.b : p0.b,
                            first_more ? m1 : m0};
    const PacketEntry sooner{first_more ? p0.a : p1.a, first_more ? p0.b : p1.b,
                             first_more ? m0 : m1};
    if (lane == 0) {
      if (later.mask) stack[top] = later;
      if (sooner.mask) stack[top + (later.mask ? 1 : 0)] = sooner;
    }
    top += (later.mask ? 1 : 0) + (sooner.mask ? 1 : 0);
    __syncwarp();
  }
}

__global__ void packet_kernel(CollisionModelView m, const float* d_q, int n,
                              const unsigned* d_order, std::uint8_t* d_verdicts,
                              DeviceTestCounts* d_counts) {
  __shared__ PacketEntry stacks[kPacketWarpsPerBlock][detail::kStackSize];
  const int warp = threadIdx.x / 32;
  const int index = (blockIdx.x * kPacketWarpsPerBlock + warp) * 32 + (threadIdx.x & 31);
  const bool valid = index < n;
  const int query = valid ? static_cast<int>(d_order[index]) : 0;
  detail::TraversalCounts counts;
  detail::Xf X_WL[detail::kMaxLinks];
  const float* q = d_q + static_cast<std::size_t>(query) * m.width;
  if (valid) detail::link_poses(m, q, X_WL);
  // A row that is no configuration collides from the start and joins no traversal.
  bool collided = valid && !detail::is_configuration(m, q);
  const float* clearances = query_clearances(m, query);
  const auto pose = [&](int l) { return X_WL[l]; };
  const auto centre = [&](int l) { return detail::sphere_center_W(m, l, X_WL[l]); };
  for (int body = 0; body < detail::body_count(m); ++body) {
    if (__all_sync(kFullMask, !valid || collided)) break;
    const detail::BodyTolerance tolerance = detail::body_tolerance(m, body, clearances);
    const bool may_touch =
        valid && !collided && detail::body_may_touch(m, body, centre, tolerance.margin);
    const unsigned active = __ballot_sync(kFullMask, may_touch);
    if (active) {
      const detail::BodyRanges r = detail::body_ranges(m, body);
      packet_traverse(m, r.a, r.b, detail::body_transform(m, body, pose), tolerance, active,
                      stacks[warp], &collided, &counts);
    }
  }
  // Each lane whose surfaces met nowhere: the containment step on its own.
  if (valid && !collided) collided = detail::query_contained(m, X_WL, clearances);
  if (valid) d_verdicts[query] = collided ? 1 : 0;
  add_counts(counts, d_counts);
}

}  // namespace

void PacketTraversal::cluster(const float* d_q, int n, int width) {
  const int k = std::max(1, n / 256);
  labels_.reserve(n);
  sorted_labels_.reserve(n);
  order_.reserve(n);
  identity_.reserve(n);
  centres_.reserve(static_cast<std::size_t>(k) * width);
  sums_.reserve(static_cast<std::size_t>(k) * width);
  cluster_counts_.reserve(k);
  kmeans_init_kernel<<<blocks_for(k * width, 256), 256>>>(d_q, n, width, centres_.get(), k);
  for (int iteration = 0; iteration < 4; ++iteration) {
    kmeans_assign_kernel<<<blocks_for(n, 256), 256>>>(d_q, n, width, centres_.get(), k,
                                                      labels_.get());
    check_cuda(cudaMemset(sums_.get(), 0, sizeof(float) * k * width), "memset");
    check_cuda(cudaMemset(cluster_counts_.get(), 0, sizeof(unsigned) * k), "memset");
    kmeans_accumulate_kernel<<<blocks_for(n, 256), 256>>>(d_q, n, width, labels_.get(), sums_.get(),
                                                          cluster_counts_.get());
    kmeans_update_kernel<<<blocks_for(k * width, 256), 256>>>(centres_.get(), sums_.get(),
                                                              cluster_counts_.get(), k, width);
  }
  kmeans_assign_kernel<<<blocks_for(n, 256), 256>>>(d_q, n, width, centres_.get(), k,
                                                    labels_.get());
  iota_kernel<<<blocks_for(n, 256), 256>>>(identity_.get(), n);
  int bits = 1;
  while ((1 << bits) < k) ++bits;
  std::size_t scratch_bytes = 0;
  cub::DeviceRadixSort::SortPairs(nullptr, scratch_bytes, labels_.get(), sorted_labels_.get(),
                                  identity_.get(), order_.get(), n, 0, bits);
  sort_scratch_.reserve(scratch_bytes);
  check_cuda(cub::DeviceRadixSort::SortPairs(sort_scratch_.get(), scratch_bytes, labels_.get(),
                                             sorted_labels_.get(), identity_.get(), order_.get(), n,
                                             0, bits),
             "sort");
}

void PacketTraversal::run(const CollisionModelView& m, const float* d_q, int n,
                          std::uint8_t* d_verdicts, DeviceTestCounts* d_counts) {
  cluster(d_q, n, m.width);
  const int packets = (n + 31) / 32;
  packet_kernel<<<blocks_for(packets, kPacketWarpsPerBlock), 32 * kPacketWarpsPerBlock>>>(
      m, d_q, n, order_.get(), d_verdicts, d_counts);
  check_cuda(cudaGetLastError(), "packet kernel");
}

}  // namespace gplanner::traversals
