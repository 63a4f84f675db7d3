// The GPU batch checker: model upload, chunking under a memory cap, and the three
// traversals. Device functions come from detail/query.h, shared with the CPU backend.

#include <cuda_runtime.h>

#include <algorithm>
#include <cstddef>
#include <cub/device/device_radix_sort.cuh>
#include <stdexcept>
#include <string>
#include <vector>

#include "gplanner/collision_gpu/detail/cuda_memory.cuh"
#include "gplanner/collision_gpu/detail/query.h"
#include "gplanner/collision_gpu/gpu_batch_checker.h"
#include "gplanner/collision_gpu/model_view.h"

namespace gplanner {
namespace {

void check_cuda(cudaError_t status, const char* what) { cuda::check(status, "CUDA", what); }

using cuda::DeviceBuffer;

constexpr int kTracedRounds = 32;

// Counters that many threads add to at once each sit on a cache line of their own: on
// one line their atomics queued behind each other at the same L2 slice (Nsight Compute
// on the H100: the waits for the fetch, leaf and hand-back atomics were 23 % of the task
// kernel's stall samples on the piano; apart, balanced was 4 to 8 % faster on the
// humanoid, piano_detailed and the PR2 scenes, the rest within the runs' spread).
struct Counters {
  alignas(128) unsigned long long bv_tests;
  unsigned long long triangle_tests;
  alignas(128) unsigned int jobs;  // balanced: jobs emitted
  unsigned int jobs_overflow;
  unsigned int next_job;  // balanced, small batches: jobs taken by warps
  // The balanced task queue, kept on the device so that rounds follow one another
  // without the host: tasks [0, top) are queued; a round takes [begin, begin + launch).
  alignas(128) unsigned int top, begin, launch;
  alignas(128) unsigned int tasks;    // children emitted by this round's task kernel
  alignas(128) unsigned int leaves;   // leaf pairs emitted by this round's task kernel
  alignas(128) unsigned int fetched;  // tasks taken by the lanes of this round's task kernel
  alignas(128) unsigned int rounds;   // rounds that had tasks
  unsigned int steps;                 // BV tests a task of this round runs at most
  unsigned int queue_full;
  unsigned int finish;                      // the queue is short: the finish kernel takes all of it
  unsigned int round_tasks[kTracedRounds];  // tasks each of the first rounds took
};

constexpr unsigned kFullMask = 0xffffffffu;

// Adds this thread's counts to the global counters, one atomic per warp.
__device__ void add_counts(const detail::TraversalCounts& counts, Counters* d_counters) {
  unsigned long long bv = counts.bv_tests, tri = counts.triangle_tests;
  for (int offset = 16; offset > 0; offset /= 2) {
    bv += __shfl_down_sync(kFullMask, bv, offset);
    tri += __shfl_down_sync(kFullMask, tri, offset);
  }
  if ((threadIdx.x & 31) == 0) {
    atomicAdd(&d_counters->bv_tests, bv);
    atomicAdd(&d_counters->triangle_tests, tri);
  }
}

// ---------------------------------------------------------------- basic

__global__ void basic_kernel(CollisionModelView m, const float* d_q, int n,
                             std::uint8_t* d_verdicts, Counters* d_counters) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  detail::TraversalCounts counts;
  if (i < n) {
    detail::Xf X_WL[detail::kMaxLinks];
    d_verdicts[i] =
        detail::query_collides(m, d_q + static_cast<std::size_t>(i) * m.width, X_WL, &counts) ? 1
                                                                                              : 0;
  }
  add_counts(counts, d_counters);
}

// ---------------------------------------------------------------- packet

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
                                const detail::Xf& X_AB, unsigned active, PacketEntry* stack,
                                bool* collided, detail::TraversalCounts* counts) {
  const unsigned lane = threadIdx.x & 31;
  const bool mine = (active >> lane) & 1u;
  auto overlaps = [&](int ia, int ib) {
    if (counts) ++counts->bv_tests;
    return detail::nodes_overlap(m.nodes[a.node_offset + ia], m.nodes[b.node_offset + ib], X_AB,
                                 m.margin);
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
                                  m.threshold)) {
          *collided = true;
        }
      }
      continue;
    }
    int a0 = entry.a, a1 = entry.a, b0 = entry.b, b1 = entry.b;
    if (detail::splits_a(na, nb)) {
      a0 = na.child;
      a1 = na.child + 1;
    } else {
      b0 = nb.child;
      b1 = nb.child + 1;
    }
    const unsigned m0 = __ballot_sync(kFullMask, in && overlaps(a0, b0));
    const unsigned m1 = __ballot_sync(kFullMask, in && overlaps(a1, b1));
    // Push the less popular pair first so that the more popular one is popped next.
    const bool first_more = __popc(m0) >= __popc(m1);
    const PacketEntry later{first_more ? a1 : a0, first_more ? b1 : b0, first_more ? m1 : m0};
    const PacketEntry sooner{first_more ? a0 : a1, first_more ? b0 : b1, first_more ? m0 : m1};
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
                              Counters* d_counters) {
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
  const int bodies = m.link_count + m.pair_count;
  for (int body = 0; body < bodies; ++body) {
    if (__all_sync(kFullMask, !valid || collided)) break;
    BodyRange a, b;
    detail::Xf X_AB;
    bool may_touch;
    if (body < m.link_count) {
      a = m.environment;
      b = m.link_bodies[body];
      X_AB = X_WL[body];
      may_touch = valid && !collided && detail::link_may_touch_environment(m, body, X_AB);
    } else {
      const int p = body - m.link_count;
      a = m.link_bodies[m.pair_a[p]];
      b = m.link_bodies[m.pair_b[p]];
      may_touch = valid && !collided && detail::pair_may_touch(m, p, X_WL);
      X_AB = geometry::inverse(X_WL[m.pair_a[p]]) * X_WL[m.pair_b[p]];
    }
    const unsigned active = __ballot_sync(kFullMask, may_touch);
    if (active) packet_traverse(m, a, b, X_AB, active, stacks[warp], &collided, &counts);
  }
  if (valid) d_verdicts[query] = collided ? 1 : 0;
  add_counts(counts, d_counters);
}

// ---------------------------------------------------------------- balanced

// One body pair of one query that survived the broad phase: the unit tasks refer to.
struct alignas(16) Job {
  int query;
  BodyRange a, b;
  float X_AB[12];
};

// A node pair of a job: an inner pair to traverse, or (in the leaf queue) two leaves
// whose triangles to test.
struct Task {
  int job, a, b;
};

__device__ void store_transform(const detail::Xf& X, float* out) {
  for (int i = 0; i < 3; ++i) {
    out[3 * i] = X.R.r[i].x;
    out[3 * i + 1] = X.R.r[i].y;
    out[3 * i + 2] = X.R.r[i].z;
  }
  out[9] = X.t.x;
  out[10] = X.t.y;
  out[11] = X.t.z;
}

// Kinematics and broad phase per query; every surviving body pair becomes a job with
// one root task.
__global__ void balanced_roots_kernel(CollisionModelView m, const float* d_q, int n, Job* d_jobs,
                                      int job_capacity, Task* d_tasks, std::uint8_t* d_verdicts,
                                      Counters* d_counters) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const float* q = d_q + static_cast<std::size_t>(i) * m.width;
  if (!detail::is_configuration(m, q)) {
    d_verdicts[i] = 1;  // no configuration: colliding, and no jobs
    return;
  }
  detail::Xf X_WL[detail::kMaxLinks];
  detail::link_poses(m, q, X_WL);
  auto emit = [&](BodyRange a, BodyRange b, const detail::Xf& X_AB) {
    const unsigned slot = atomicAdd(&d_counters->jobs, 1u);
    if (slot >= static_cast<unsigned>(job_capacity)) {
      d_counters->jobs_overflow = 1;
      return;
    }
    Job job;
    job.query = i;
    job.a = a;
    job.b = b;
    store_transform(X_AB, job.X_AB);
    d_jobs[slot] = job;
    d_tasks[slot] = {static_cast<int>(slot), 0, 0};
  };
  for (int l = 0; l < m.link_count; ++l) {
    if (detail::link_may_touch_environment(m, l, X_WL[l]))
      emit(m.environment, m.link_bodies[l], X_WL[l]);
  }
  for (int p = 0; p < m.pair_count; ++p) {
    if (detail::pair_may_touch(m, p, X_WL)) {
      emit(m.link_bodies[m.pair_a[p]], m.link_bodies[m.pair_b[p]],
           geometry::inverse(X_WL[m.pair_a[p]]) * X_WL[m.pair_b[p]]);
    }
  }
}

// The same for articulated robots with many links and pairs, a warp per query: the
// joint transforms and every bounding-sphere test spread over the lanes (one thread
// would run them one after another: 130 us for a PR2 arm's 519 tests), only the
// composition of the poses down the tree in one lane. Jobs are appended with one atomic
// per warp and 32 tests. Used for batches of up to kWarpRootsUpTo queries: in larger
// ones the GPU is full either way, and a query's jobs side by side (rather than
// interleaved with other queries' as the thread-per-query kernel leaves them) made the
// first rounds' lanes work on fewer queries at once and did up to 37 % more BV tests
// (measured on the H100: the humanoid at 100,000 queries 10.5 ms with a thread per
// query against 12.6 ms; at 3,000 and 10,000 queries a warp per query was faster or
// tied on the humanoid and both PR2 scenes).
constexpr int kRootWarps = 4;  // warps (queries) per block
constexpr std::size_t kWarpRootsUpTo = 16384;

__global__ void __launch_bounds__(32 * kRootWarps)
    balanced_roots_warp_kernel(CollisionModelView m, const float* d_q, int n, Job* d_jobs,
                               int job_capacity, Task* d_tasks, std::uint8_t* d_verdicts,
                               Counters* d_counters) {
  __shared__ float s_poses[kRootWarps][detail::kMaxLinks][12];  // X_PL, then X_WL
  __shared__ float4 s_spheres[kRootWarps][detail::kMaxLinks];   // centre in the world
  const int warp = threadIdx.x / 32;
  const unsigned lane = threadIdx.x & 31;
  const int i = blockIdx.x * kRootWarps + warp;
  if (i >= n) return;  // the whole warp
  const float* q = d_q + static_cast<std::size_t>(i) * m.width;
  if (!detail::is_configuration(m, q)) {
    if (lane == 0) d_verdicts[i] = 1;  // no configuration: colliding, and no jobs
    return;
  }
  float(*poses)[12] = s_poses[warp];
  for (int l = static_cast<int>(lane); l < m.link_count; l += 32)
    store_transform(l == 0 ? detail::base_pose(m, q) : detail::joint_transform(m, l, q), poses[l]);
  __syncwarp();
  if (lane == 0) {
    for (int l = 1; l < m.link_count; ++l) {
      store_transform(
          detail::load_transform(poses[m.links[l].parent]) * detail::load_transform(poses[l]),
          poses[l]);
    }
  }
  __syncwarp();
  for (int l = static_cast<int>(lane); l < m.link_count; l += 32) {
    const detail::V3f c = detail::sphere_center_W(m, l, detail::load_transform(poses[l]));
    s_spheres[warp][l] = make_float4(c.x, c.y, c.z, 0.0f);
  }
  __syncwarp();
  auto centre = [&](int l) {
    const float4 c = s_spheres[warp][l];
    return detail::V3f{c.x, c.y, c.z};
  };
  // Body b < link_count: link b against the environment; otherwise pair b - link_count.
  const int bodies = m.link_count + m.pair_count;
  for (int start = 0; start < bodies; start += 32) {
    const int b = start + static_cast<int>(lane);
    bool touch = false;
    if (b < m.link_count) {
      touch = detail::sphere_may_touch_environment(m, b, centre(b));
    } else if (b < bodies) {
      const int p = b - m.link_count;
      touch = detail::spheres_may_touch(m, p, centre(m.pair_a[p]), centre(m.pair_b[p]));
    }
    const unsigned touching = __ballot_sync(kFullMask, touch);
    if (touching == 0) continue;
    unsigned base = 0;
    const int leader = __ffs(touching) - 1;
    if (lane == static_cast<unsigned>(leader))
      base = atomicAdd(&d_counters->jobs, static_cast<unsigned>(__popc(touching)));
    base = __shfl_sync(kFullMask, base, leader);
    if (!touch) continue;
    const unsigned slot = base + __popc(touching & ((1u << lane) - 1u));
    if (slot >= static_cast<unsigned>(job_capacity)) {
      d_counters->jobs_overflow = 1;
      continue;
    }
    Job job;
    job.query = i;
    if (b < m.link_count) {
      job.a = m.environment;
      job.b = m.link_bodies[b];
      for (int k = 0; k < 12; ++k) job.X_AB[k] = poses[b][k];
    } else {
      const int p = b - m.link_count;
      job.a = m.link_bodies[m.pair_a[p]];
      job.b = m.link_bodies[m.pair_b[p]];
      store_transform(geometry::inverse(detail::load_transform(poses[m.pair_a[p]])) *
                          detail::load_transform(poses[m.pair_b[p]]),
                      job.X_AB);
    }
    d_jobs[slot] = job;
    d_tasks[slot] = {static_cast<int>(slot), 0, 0};
  }
}

// Small batches: a warp per job, taken in turn by the resident warps, its node pairs
// on a stack in shared memory and tested up to 32 at a time (the top of the stack:
// depth first across steps, breadth first within one), triangle tests in the same
// kernel. More BV tests than the task rounds make (the early exit comes later), but a
// whole batch in one launch: when the GPU has room to spare, a call's time is its longest
// chain of dependent tests, and each round of tasks adds a launch to that chain.
//
// Stack bound: node pairs are pushed in order of depth, so all pairs of one depth lie
// above those of the depth before; a step that pops a pair of depth t - 1 pops every
// pair of depth t with it, and pushes at most 64 of depth t. At most 64 pairs per depth,
// 64 * (traversal_depth + 1) in all: stack_capacity.
constexpr int kPairWarps = 4;  // warps per block at most

//
// kFinish: the same for what a traversal's rounds left in a short queue (Counters::
// finish), a warp per task from its node pair, instead of more rounds of a few tasks each,
// whose cost is their launches and dependent steps whatever their size.
template <bool kFinish>
__global__ void __launch_bounds__(32 * kPairWarps)
    balanced_warp_per_pair_kernel(CollisionModelView m, const Job* d_jobs, const Task* d_tasks,
                                  int stack_capacity, std::uint8_t* d_collided,
                                  Counters* d_counters) {
  extern __shared__ int2 s_stacks[];
  if (d_counters->jobs_overflow) return;  // the host runs the chunk again, smaller
  if (kFinish && !d_counters->finish) return;
  const unsigned jobs = kFinish ? d_counters->top : d_counters->jobs;
  const unsigned lane = threadIdx.x & 31;
  int2* stack = s_stacks + static_cast<std::size_t>(threadIdx.x / 32) * stack_capacity;
  volatile std::uint8_t* collided_flags = d_collided;
  detail::TraversalCounts counts;
  while (true) {
    unsigned j = 0;
    if (lane == 0) j = atomicAdd(&d_counters->next_job, 1u);
    j = __shfl_sync(kFullMask, j, 0);
    if (j >= jobs) break;
    const Task task = kFinish ? d_tasks[j] : Task{static_cast<int>(j), 0, 0};
    const Job& job = d_jobs[task.job];
    const int query = job.query;
    if (__shfl_sync(kFullMask, lane == 0 ? collided_flags[query] : 0, 0)) continue;
    const BodyRange body_a = job.a, body_b = job.b;
    const detail::Xf X_AB = detail::load_transform(job.X_AB);
    if (lane == 0) stack[0] = make_int2(task.a, task.b);
    __syncwarp();
    int top = 1;
    bool collided = false;
    for (int step = 1; top > 0; ++step) {
      const int take = min(top, 32);
      const bool active = static_cast<int>(lane) < take;
      int2 pair = make_int2(0, 0);
      if (active) pair = stack[top - take + static_cast<int>(lane)];
      __syncwarp();
      top -= take;
      bool hit = false, split = false;
      detail::NodePair first{}, second{};
      if (active) {
        const BvhNode& na = m.nodes[body_a.node_offset + pair.x];
        const BvhNode& nb = m.nodes[body_b.node_offset + pair.y];
        ++counts.bv_tests;
        if (detail::nodes_overlap(na, nb, X_AB, m.margin)) {
          if (na.is_leaf() && nb.is_leaf()) {
            ++counts.triangle_tests;
            hit = detail::leaf_collides(m.triangles[body_a.triangle_offset + na.triangle()],
                                        m.triangles[body_b.triangle_offset + nb.triangle()], X_AB,
                                        m.threshold);
          } else {
            // split_pair's rule without its order of the children (which loads both):
            // the next step tests them side by side anyway.
            if (detail::splits_a(na, nb)) {
              first = {na.child, pair.y};
              second = {na.child + 1, pair.y};
            } else {
              first = {pair.x, nb.child};
              second = {pair.x, nb.child + 1};
            }
            split = true;
          }
        }
      }
      if (__any_sync(kFullMask, hit)) {
        collided = true;
        break;
      }
      const unsigned splitting = __ballot_sync(kFullMask, split);
      if (split) {
        const int at = top + 2 * __popc(splitting & ((1u << lane) - 1u));
        stack[at] = make_int2(second.a, second.b);
        stack[at + 1] = make_int2(first.a, first.b);
      }
      top += 2 * __popc(splitting);
      __syncwarp();
      // Another job of the query may have found a collision.
      if ((step & 7) == 0 && __shfl_sync(kFullMask, lane == 0 ? collided_flags[query] : 0, 0))
        break;
    }
    if (collided && lane == 0) collided_flags[query] = 1;
  }
  add_counts(counts, d_counters);
}

// Steps of depth-first traversal one task runs before it hands what is left of its
// stack back to the queue: short enough that the work of one hard query spreads over
// many threads in the next launch, long enough that a query finding a collision stops
// its own search early.
constexpr int kTaskSteps = 32;
// Threads per block of the task kernel, with kStackEntries stack entries each in shared
// memory (how many blocks an SM holds is set by the carve-out). Measured on the H100 at
// 50,000 to 100,000 queries against 256 threads with stacks in local memory: 4 to 17 %
// faster on every scene; 16-step tasks did more BV tests and were slower than either.
constexpr int kTaskThreads = 128;
// A task whose stack fills hands it back before its steps are used up. 24 entries
// (25 KB a block) let six blocks share an SM's 164 KB of shared memory where the 33 that
// 32 steps can reach let four; few stacks grow that deep. Measured on the H100 in one run,
// two passes, against 33 entries: the humanoid 11 to 14 % faster, pr2_base_arm 10 to
// 11 %, pr2_reach 4 to 6 %, the large piano 3 to 4 % slower, the rest within 3 %; 16
// entries handed back so often that the traversals did 8 to 87 % more BV tests and were
// slower everywhere.
constexpr int kStackEntries = 24;
// Once a round has fewer tasks than kTailTasks the GPU has room to spare, and tasks run
// kTailSteps: the remaining hard queries spread over more threads sooner.
constexpr unsigned kTailTasks = 65536;
constexpr unsigned kTailSteps = 8;
// After two rounds, a queue of at most kFinishTasks tasks is finished by one launch of
// the small-batch kernel, a warp per task, instead of the rounds of a few tasks each
// that remained (measured on an H200 against no finish, the same run: 50,000 to 100,000
// queries 0 to 7 % faster on every scene, 300 to 4,000 queries 12 to 34 %).
constexpr unsigned kFinishTasks = 4096;

// Tasks fetched lane by lane: each lane runs up to kTaskSteps BV-pair tests depth-first
// from its task's node pair and, as soon as its task ends (stack empty, steps used up, or
// the query found colliding), takes the next task of the launch, so that the lanes of a
// warp stay busy although their tasks end at very different steps. Overlapping leaf
// pairs go to the leaf queue, tested by balanced_leaf_kernel (the double-precision
// triangle test would otherwise stall the whole warp and, with its registers, cut the
// threads that fit); the node pairs left on a stack become new tasks in d_children (one
// atomic per warp and step at which some lane hands its stack back).
__global__ void __launch_bounds__(kTaskThreads, 6)
    balanced_task_kernel(CollisionModelView m, const Job* d_jobs, const Task* d_queue,
                         Task* d_children, Task* d_leaves, unsigned leaf_capacity,
                         const std::uint8_t* d_collided, Counters* d_counters) {
  const unsigned count = d_counters->launch;
  if (count == 0) return;  // the queue ran empty in an earlier round of this burst
  const Task* d_tasks = d_queue + d_counters->begin;
  const unsigned lane = threadIdx.x & 31;
  detail::TraversalCounts counts;
  // Each step pops one pair and pushes at most two; a stack that reaches kStackEntries
  // is handed back. The stacks live in shared memory, entry k of all threads side by
  // side, so that a lane always meets the same bank whatever its depth: in local memory
  // they missed the L1 and stalled the warps on L2 (Nsight Compute on the H100: 19
  // cycles of long-scoreboard stall an instruction in the big rounds).
  __shared__ int2 s_stacks[kStackEntries][kTaskThreads];
  int2* stack = &s_stacks[0][threadIdx.x];
  int top = 0, job_index = 0, query = 0;
  unsigned steps = 0;
  BodyRange body_a{}, body_b{};
  detail::Xf X_AB{}, X_BA{};
  const unsigned max_steps = d_counters->steps;
  const unsigned threads = gridDim.x * blockDim.x;
  bool exhausted = false, first = true;
  while (__any_sync(kFullMask, top > 0 || !exhausted)) {
    // Lanes without a task take the next ones: the first by thread index, the later ones
    // beyond all threads' first through one atomic per warp.
    const bool fetch = top == 0 && !exhausted;
    const unsigned fetching = __ballot_sync(kFullMask, fetch);
    if (fetching) {
      unsigned base = 0;
      if (!first) {
        const int leader = __ffs(fetching) - 1;
        if (lane == static_cast<unsigned>(leader))
          base = atomicAdd(&d_counters->fetched, static_cast<unsigned>(__popc(fetching)));
        base = __shfl_sync(kFullMask, base, leader);
      }
      if (fetch) {
        const unsigned index = first ? blockIdx.x * blockDim.x + threadIdx.x
                                     : threads + base + __popc(fetching & ((1u << lane) - 1u));
        if (index >= count) {
          exhausted = true;
        } else {
          const Task task = d_tasks[index];
          const Job& job = d_jobs[task.job];
          job_index = task.job;
          query = job.query;
          if (!d_collided[query]) {
            body_a = job.a;
            body_b = job.b;
            X_AB = detail::load_transform(job.X_AB);
            X_BA = geometry::inverse(X_AB);
            stack[0] = make_int2(task.a, task.b);
            top = 1;
            steps = 0;
          }
        }
      }
      first = false;
    }
    bool hand_back = false;
    if (top > 0) {
      if ((steps & 7) == 7 && d_collided[query]) {
        top = 0;  // a leaf test of this query found a collision
      } else {
        ++steps;
        --top;
        const int2 pair = stack[top * kTaskThreads];
        const int ia = pair.x, ib = pair.y;
        const BvhNode& na = m.nodes[body_a.node_offset + ia];
        const BvhNode& nb = m.nodes[body_b.node_offset + ib];
        ++counts.bv_tests;
        if (detail::nodes_overlap(na, nb, X_AB, m.margin)) {
          if (na.is_leaf() && nb.is_leaf()) {
            const unsigned slot = atomicAdd(&d_counters->leaves, 1u);
            if (slot < leaf_capacity) {
              d_leaves[slot] = {job_index, na.triangle(), nb.triangle()};
            } else {
              ++top;  // the leaf queue is full: keep the pair as a task for the next launch
              hand_back = true;
            }
          } else {
            detail::NodePair first, second;
            detail::split_pair(X_AB, X_BA, ia, ib, na, nb, &first, &second);
            stack[top * kTaskThreads] = make_int2(second.a, second.b);
            stack[(top + 1) * kTaskThreads] = make_int2(first.a, first.b);
            top += 2;
          }
        }
        if (top > 0 && (steps == max_steps || top >= kStackEntries)) hand_back = true;
      }
    }
    // Warp-aggregated append of the stacks handed back.
    const int leaving = hand_back ? top : 0;
    if (__any_sync(kFullMask, leaving > 0)) {
      int offset = leaving;
      for (int d = 1; d < 32; d *= 2) {
        const int other = __shfl_up_sync(kFullMask, offset, d);
        if (lane >= static_cast<unsigned>(d)) offset += other;
      }
      const int total = __shfl_sync(kFullMask, offset, 31);
      unsigned base = 0;
      if (lane == 31) base = atomicAdd(&d_counters->tasks, static_cast<unsigned>(total));
      base = __shfl_sync(kFullMask, base, 31);
      const unsigned at = base + offset - leaving;
      for (int k = 0; k < leaving; ++k) {
        const int2 pair = stack[k * kTaskThreads];
        d_children[at + k] = {job_index, pair.x, pair.y};
      }
    }
    if (hand_back) top = 0;
  }
  add_counts(counts, d_counters);
}

// The leaf pairs of a round, a thread each (grid-stride): the triangle test, marking the
// query when it collides. The same kernel moves the round's children into the queue
// where its tasks were taken from.
__global__ void __launch_bounds__(256, 2)
    balanced_leaf_kernel(CollisionModelView m, const Job* d_jobs, const Task* d_leaves,
                         unsigned leaf_capacity, const Task* d_children, Task* d_queue,
                         std::uint8_t* d_collided, Counters* d_counters) {
  const unsigned leaves = min(d_counters->leaves, leaf_capacity);
  const unsigned children = d_counters->tasks;
  Task* d_to = d_queue + d_counters->begin;
  const unsigned stride = gridDim.x * blockDim.x;
  for (unsigned t = blockIdx.x * blockDim.x + threadIdx.x; t < children; t += stride)
    d_to[t] = d_children[t];
  if (leaves == 0) return;
  detail::TraversalCounts counts;
  for (unsigned t = blockIdx.x * blockDim.x + threadIdx.x; t < leaves; t += stride) {
    const Task leaf = d_leaves[t];
    const Job& job = d_jobs[leaf.job];
    if (!d_collided[job.query]) {
      ++counts.triangle_tests;
      if (detail::leaf_collides(m.triangles[job.a.triangle_offset + leaf.a],
                                m.triangles[job.b.triangle_offset + leaf.b],
                                detail::load_transform(job.X_AB), m.threshold)) {
        d_collided[job.query] = 1;
      }
    }
  }
  add_counts(counts, d_counters);
}

// Ends a round: the children join the queue, and the next round takes the newest tasks
// (depth-first across rounds, which keeps the queue short), as many as leave room for
// their children.
__device__ void advance_queue(Counters& c, unsigned task_capacity, unsigned max_launch) {
  const unsigned top = c.begin + c.tasks;
  // A task leaves at most kStackEntries pairs in place of itself.
  const unsigned room = (task_capacity - top) / kStackEntries;
  const unsigned launch = min(top, min(room, max_launch));
  if (top > 0 && launch == 0) c.queue_full = 1;
  // A short queue goes to the finish kernel whole; the rounds' kernels then do nothing.
  c.finish = top > 0 && top <= kFinishTasks && c.rounds >= 2 ? 1 : 0;
  c.top = top;
  c.launch = c.finish ? 0 : launch;
  c.begin = top - c.launch;
  c.tasks = 0;
  c.leaves = 0;
  c.fetched = 0;
  c.steps = launch < kTailTasks ? kTailSteps : kTaskSteps;
  if (c.launch > 0) {
    if (c.rounds < kTracedRounds) c.round_tasks[c.rounds] = c.launch;
    ++c.rounds;
  }
}

__global__ void balanced_advance_kernel(Counters* d_counters, unsigned task_capacity,
                                        unsigned max_launch) {
  advance_queue(*d_counters, task_capacity, max_launch);
}

// Starts a chunk's traversal after the roots kernel: the jobs' root tasks fill the
// queue, as if a round at 0 had emitted them. When the jobs overflowed their buffer no
// round runs (the host sees the flag and runs the chunk again, smaller).
__global__ void balanced_start_kernel(Counters* d_counters, unsigned task_capacity,
                                      unsigned max_launch) {
  Counters& c = *d_counters;
  c.begin = 0;
  c.tasks = c.jobs_overflow ? 0 : c.jobs;
  c.rounds = 0;
  c.queue_full = 0;
  advance_queue(c, task_capacity, max_launch);
}

int blocks_for(std::size_t n, int threads) { return static_cast<int>((n + threads - 1) / threads); }

}  // namespace

struct GpuBatchChecker::Impl {
  GpuCheckerOptions options;
  FlatCollisionModel host;
  CollisionModelView view{};
  std::string device_name;
  std::size_t memory_cap = 0;
  int resident_task_blocks = 1;  // balanced: blocks of each kernel resident at once
  int resident_leaf_blocks = 1;
  // balanced: whether a query has more link and pair sphere tests than a warp has lanes;
  // then batches of up to kWarpRootsUpTo queries run kinematics and broad phase a warp
  // per query.
  bool many_bodies = false;
  int pair_stack_capacity = 0;        // balanced, small batches: node pairs per warp's stack
  int pair_warps = 1;                 // warps (stacks) per block of the small-batch kernel
  int pair_blocks = 1;                // resident blocks of the small-batch kernel
  std::size_t pair_shared_bytes = 0;  // its dynamic shared memory: pair_warps stacks
  GpuCheckStats stats;

  DeviceBuffer<LinkKinematics> links;
  DeviceBuffer<BodyRange> link_bodies;
  DeviceBuffer<LinkSphere> link_spheres;
  DeviceBuffer<BvhNode> nodes;
  DeviceBuffer<BvhTriangle> triangles;
  DeviceBuffer<std::int32_t> pair_a, pair_b;

  DeviceBuffer<float> configurations;
  DeviceBuffer<std::uint8_t> verdicts;
  DeviceBuffer<Counters> counters;
  // packet
  DeviceBuffer<unsigned> labels, sorted_labels, order, identity;
  DeviceBuffer<float> centres, sums;
  DeviceBuffer<unsigned> cluster_counts;
  DeviceBuffer<unsigned char> sort_scratch;
  // balanced
  DeviceBuffer<Job> jobs;
  DeviceBuffer<Task> tasks, children, leaves;

  Impl(const CollisionModel& model, const GpuCheckerOptions& o) : options(o), host(model) {
    int count = 0;
    check_cuda(cudaGetDeviceCount(&count), "no usable GPU");
    if (count == 0) throw std::runtime_error("no CUDA device found");
    cudaDeviceProp properties{};
    check_cuda(cudaGetDeviceProperties(&properties, 0), "cudaGetDeviceProperties");
    device_name = properties.name;
    int blocks_per_sm = 0;
    // The shared-memory share of the SM's 256 KB of L1 and shared memory that the task
    // kernel asks for, in percent of the largest (the driver rounds it to a size the SM
    // has): measured on the H100, with 33-entry stacks, at 100 (28 KB of L1 left for the
    // nodes), 80, 60 and 40: 60 and 80 were fastest, 60 on more scenes; 100 and 40 were
    // 11 to 51 % slower than 60. With 24-entry stacks, 60 (164 KB) holds six blocks; 50
    // (five blocks, more L1) was 4 to 6 % faster on the two detailed pianos and up to 7 %
    // slower on the humanoid.
    check_cuda(cudaFuncSetAttribute(balanced_task_kernel,
                                    cudaFuncAttributePreferredSharedMemoryCarveout, 60),
               "carve-out");
    check_cuda(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&blocks_per_sm, balanced_task_kernel,
                                                             kTaskThreads, 0),
               "occupancy");
    resident_task_blocks = std::max(1, blocks_per_sm) * properties.multiProcessorCount;
    check_cuda(
        cudaOccupancyMaxActiveBlocksPerMultiprocessor(&blocks_per_sm, balanced_leaf_kernel, 256, 0),
        "occupancy");
    resident_leaf_blocks = std::max(1, blocks_per_sm) * properties.multiProcessorCount;
    std::size_t free_bytes = 0, total_bytes = 0;
    check_cuda(cudaMemGetInfo(&free_bytes, &total_bytes), "cudaMemGetInfo");
    memory_cap = options.memory_cap_bytes ? options.memory_cap_bytes : free_bytes / 2;

    links.upload(host.links);
    link_bodies.upload(host.link_bodies);
    link_spheres.upload(host.link_spheres);
    nodes.upload(host.nodes);
    triangles.upload(host.triangles);
    pair_a.upload(host.pair_a);
    pair_b.upload(host.pair_b);
    counters.reserve(1);
    view = host.view();
    view.links = links.get();
    view.link_bodies = link_bodies.get();
    view.link_spheres = link_spheres.get();
    view.nodes = nodes.get();
    view.triangles = triangles.get();
    view.pair_a = pair_a.get();
    view.pair_b = pair_b.get();
    many_bodies = view.link_count + view.pair_count > 32;
    pair_stack_capacity = 64 * (host.traversal_depth + 1);
    const std::size_t stack_bytes = pair_stack_capacity * sizeof(int2);  // at most 66 KB
    pair_warps = static_cast<int>(
        std::clamp<std::size_t>(properties.sharedMemPerBlockOptin / stack_bytes, 1, kPairWarps));
    pair_shared_bytes = pair_warps * stack_bytes;
    for (auto* kernel : {balanced_warp_per_pair_kernel<false>, balanced_warp_per_pair_kernel<true>})
      check_cuda(cudaFuncSetAttribute(kernel, cudaFuncAttributeMaxDynamicSharedMemorySize,
                                      static_cast<int>(pair_shared_bytes)),
                 "shared memory of the small-batch kernel");
    check_cuda(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&blocks_per_sm,
                                                             balanced_warp_per_pair_kernel<false>,
                                                             32 * pair_warps, pair_shared_bytes),
               "occupancy");
    pair_blocks = std::max(1, blocks_per_sm) * properties.multiProcessorCount;
  }

  Counters read_counters() {
    Counters c;
    check_cuda(cudaMemcpy(&c, counters.get(), sizeof(c), cudaMemcpyDeviceToHost), "read counters");
    return c;
  }

  // Queries per chunk under the memory cap, for `bytes_per_query` of chunk-sized buffers.
  std::size_t chunk_size(std::size_t n, std::size_t bytes_per_query, double share) const {
    const std::size_t fit = static_cast<std::size_t>(share * memory_cap) / bytes_per_query;
    return std::max<std::size_t>(1, std::min(n, fit));
  }

  void run_basic(int n) {
    basic_kernel<<<blocks_for(n, 128), 128>>>(view, configurations.get(), n, verdicts.get(),
                                              counters.get());
    check_cuda(cudaGetLastError(), "basic kernel");
  }

  void run_packet(int n) {
    const int width = view.width;
    const int k = std::max(1, n / 256);
    labels.reserve(n);
    sorted_labels.reserve(n);
    order.reserve(n);
    identity.reserve(n);
    centres.reserve(static_cast<std::size_t>(k) * width);
    sums.reserve(static_cast<std::size_t>(k) * width);
    cluster_counts.reserve(k);
    kmeans_init_kernel<<<blocks_for(k * width, 256), 256>>>(configurations.get(), n, width,
                                                            centres.get(), k);
    for (int iteration = 0; iteration < 4; ++iteration) {
      kmeans_assign_kernel<<<blocks_for(n, 256), 256>>>(configurations.get(), n, width,
                                                        centres.get(), k, labels.get());
      check_cuda(cudaMemset(sums.get(), 0, sizeof(float) * k * width), "memset");
      check_cuda(cudaMemset(cluster_counts.get(), 0, sizeof(unsigned) * k), "memset");
      kmeans_accumulate_kernel<<<blocks_for(n, 256), 256>>>(
          configurations.get(), n, width, labels.get(), sums.get(), cluster_counts.get());
      kmeans_update_kernel<<<blocks_for(k * width, 256), 256>>>(centres.get(), sums.get(),
                                                                cluster_counts.get(), k, width);
    }
    kmeans_assign_kernel<<<blocks_for(n, 256), 256>>>(configurations.get(), n, width, centres.get(),
                                                      k, labels.get());
    iota_kernel<<<blocks_for(n, 256), 256>>>(identity.get(), n);
    int bits = 1;
    while ((1 << bits) < k) ++bits;
    std::size_t scratch_bytes = 0;
    cub::DeviceRadixSort::SortPairs(nullptr, scratch_bytes, labels.get(), sorted_labels.get(),
                                    identity.get(), order.get(), n, 0, bits);
    sort_scratch.reserve(scratch_bytes);
    check_cuda(cub::DeviceRadixSort::SortPairs(sort_scratch.get(), scratch_bytes, labels.get(),
                                               sorted_labels.get(), identity.get(), order.get(), n,
                                               0, bits),
               "sort");
    const int packets = (n + 31) / 32;
    packet_kernel<<<blocks_for(packets, kPacketWarpsPerBlock), 32 * kPacketWarpsPerBlock>>>(
        view, configurations.get(), n, order.get(), verdicts.get(), counters.get());
    check_cuda(cudaGetLastError(), "packet kernel");
  }

  // Returns false when the chunk emitted more jobs than fit: run it again, smaller.
  bool run_balanced(int n, std::size_t job_capacity, std::size_t task_capacity,
                    std::size_t children_capacity, std::size_t leaf_capacity) {
    check_cuda(cudaMemset(verdicts.get(), 0, n), "memset");
    const bool warp_roots = many_bodies && static_cast<std::size_t>(n) <= kWarpRootsUpTo;
    if (warp_roots) {
      balanced_roots_warp_kernel<<<blocks_for(n, kRootWarps), 32 * kRootWarps>>>(
          view, configurations.get(), n, jobs.get(), static_cast<int>(job_capacity), tasks.get(),
          verdicts.get(), counters.get());
    } else {
      balanced_roots_kernel<<<blocks_for(n, 128), 128>>>(
          view, configurations.get(), n, jobs.get(), static_cast<int>(job_capacity), tasks.get(),
          verdicts.get(), counters.get());
    }
    check_cuda(cudaGetLastError(), "balanced roots kernel");
    stats.root_lanes = warp_roots ? 32 : 1;
    const std::size_t small_batch = options.warp_per_pair_up_to != GpuCheckerOptions::kAuto
                                        ? options.warp_per_pair_up_to
                                    : many_bodies ? 1024
                                                  : 10;
    if (static_cast<std::size_t>(n) <= small_batch) {
      balanced_warp_per_pair_kernel<false><<<pair_blocks, 32 * pair_warps, pair_shared_bytes>>>(
          view, jobs.get(), nullptr, pair_stack_capacity, verdicts.get(), counters.get());
      check_cuda(cudaGetLastError(), "balanced small-batch kernel");
      stats.warp_per_pair = true;
      const Counters c = read_counters();
      if (c.jobs_overflow) return false;
      stats.jobs += c.jobs;
      return true;
    }
    // Each task may leave up to kStackEntries node pairs behind.
    const unsigned max_launch =
        static_cast<unsigned>(std::min<std::size_t>(1u << 20, children_capacity / kStackEntries));
    const unsigned capacity = static_cast<unsigned>(std::min<std::size_t>(task_capacity, ~0u));
    balanced_start_kernel<<<1, 1>>>(counters.get(), capacity, max_launch);
    Counters c;
    // Rounds run in bursts without the host; the queue is read between bursts, and a
    // round after the queue ran empty costs three near-empty launches.
    int burst = 4;
    while (true) {
      for (int r = 0; r < burst; ++r) {
        balanced_task_kernel<<<resident_task_blocks, kTaskThreads>>>(
            view, jobs.get(), tasks.get(), children.get(), leaves.get(),
            static_cast<unsigned>(leaf_capacity), verdicts.get(), counters.get());
        balanced_leaf_kernel<<<resident_leaf_blocks, 256>>>(
            view, jobs.get(), leaves.get(), static_cast<unsigned>(leaf_capacity), children.get(),
            tasks.get(), verdicts.get(), counters.get());
        balanced_advance_kernel<<<1, 1>>>(counters.get(), capacity, max_launch);
      }
      // Nothing to do unless a round left a short queue (then the rounds above it did
      // nothing either).
      balanced_warp_per_pair_kernel<true><<<pair_blocks, 32 * pair_warps, pair_shared_bytes>>>(
          view, jobs.get(), tasks.get(), pair_stack_capacity, verdicts.get(), counters.get());
      check_cuda(cudaGetLastError(), "balanced traversal kernels");
      c = read_counters();
      if (c.jobs_overflow) return false;
      if (c.queue_full)
        throw std::runtime_error("balanced traversal: task queue full; lower the batch size");
      if (c.finish || c.top == 0) break;
    }
    stats.rounds += c.rounds;
    stats.jobs += c.jobs;
    if (c.finish) stats.finished_tasks += c.top;
    for (unsigned r = 0; r < std::min<unsigned>(c.rounds, kTracedRounds); ++r)
      stats.round_tasks.push_back(c.round_tasks[r]);
    return true;
  }

  void check(const float* h_q, std::size_t n, std::uint8_t* h_verdicts) {
    stats = {};
    if (n == 0) return;
    const std::size_t width = view.width;
    const std::size_t per_query = width * sizeof(float) + 1 + 4 * sizeof(unsigned);
    std::size_t chunk =
        chunk_size(n, per_query, options.traversal == Traversal::kBalanced ? 0.1 : 0.9);
    std::size_t job_capacity = 0, task_capacity = 0, children_capacity = 0, leaf_capacity = 0;
    if (options.traversal == Traversal::kBalanced) {
      const std::size_t bodies = static_cast<std::size_t>(view.link_count) + view.pair_count;
      // Shares of the memory cap, each also bounded outright (16M jobs, 128M queued
      // tasks: far above what the shipped scenes reach) so that a large free memory is
      // not claimed for nothing. A chunk whose jobs overflow is rerun at half the size.
      job_capacity =
          std::min({chunk * bodies, static_cast<std::size_t>(0.3 * memory_cap) / sizeof(Job),
                    std::size_t(1) << 24});
      task_capacity =
          std::max<std::size_t>(2 * job_capacity + 4 * kStackEntries,
                                std::min(static_cast<std::size_t>(0.25 * memory_cap) / sizeof(Task),
                                         std::size_t(1) << 27));
      jobs.reserve(job_capacity);
      tasks.reserve(task_capacity);
      children_capacity = std::min<std::size_t>(task_capacity, std::size_t(kStackEntries) << 20);
      children.reserve(children_capacity);
      leaf_capacity = std::max<std::size_t>(
          1024, std::min<std::size_t>(std::size_t(1) << 22,
                                      static_cast<std::size_t>(0.05 * memory_cap) / sizeof(Task)));
      leaves.reserve(leaf_capacity);
    }
    configurations.reserve(chunk * width);
    verdicts.reserve(chunk);
    check_cuda(cudaMemset(counters.get(), 0, sizeof(Counters)), "memset");

    cudaEvent_t start, stop;
    check_cuda(cudaEventCreate(&start), "event");
    check_cuda(cudaEventCreate(&stop), "event");
    check_cuda(cudaEventRecord(start), "event");
    std::size_t done = 0;
    while (done < n) {
      const std::size_t count = std::min(chunk, n - done);
      check_cuda(cudaMemcpy(configurations.get(), h_q + done * width, count * width * sizeof(float),
                            cudaMemcpyHostToDevice),
                 "upload configurations");
      const int m = static_cast<int>(count);
      if (options.traversal == Traversal::kBasic) {
        run_basic(m);
      } else if (options.traversal == Traversal::kPacket) {
        run_packet(m);
      } else {
        static_assert(offsetof(Counters, jobs_overflow) == offsetof(Counters, jobs) + 4 &&
                      offsetof(Counters, next_job) == offsetof(Counters, jobs) + 8);
        check_cuda(
            cudaMemsetAsync(reinterpret_cast<char*>(counters.get()) + offsetof(Counters, jobs), 0,
                            3 * sizeof(unsigned)),
            "memset");
        if (!run_balanced(m, job_capacity, task_capacity, children_capacity, leaf_capacity)) {
          if (chunk == 1)
            throw std::runtime_error("balanced traversal: one query needs more jobs than fit");
          chunk = std::max<std::size_t>(1, chunk / 2);
          continue;  // the same queries again, fewer at a time
        }
      }
      check_cuda(cudaMemcpy(h_verdicts + done, verdicts.get(), count, cudaMemcpyDeviceToHost),
                 "download verdicts");
      done += count;
      ++stats.chunks;
    }
    check_cuda(cudaEventRecord(stop), "event");
    check_cuda(cudaEventSynchronize(stop), "event");
    float ms = 0;
    check_cuda(cudaEventElapsedTime(&ms, start, stop), "event");
    cudaEventDestroy(start);
    cudaEventDestroy(stop);
    const Counters c = read_counters();
    stats.milliseconds = ms;
    stats.bv_tests = c.bv_tests;
    stats.triangle_tests = c.triangle_tests;
  }
};

GpuBatchChecker::GpuBatchChecker(const CollisionModel& model, const GpuCheckerOptions& options)
    : impl_(std::make_unique<Impl>(model, options)) {}

GpuBatchChecker::~GpuBatchChecker() = default;

void GpuBatchChecker::check(const float* configurations, std::size_t n, std::uint8_t* verdicts) {
  impl_->check(configurations, n, verdicts);
}

const GpuCheckStats& GpuBatchChecker::last_stats() const { return impl_->stats; }

std::string GpuBatchChecker::device_name() const { return impl_->device_name; }

}  // namespace gplanner
