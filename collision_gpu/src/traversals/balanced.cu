#include "traversals/balanced.cuh"

#include <algorithm>
#include <stdexcept>

namespace gplanner::traversals {
namespace {

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
                                      BalancedState* d_state) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const float* q = d_q + static_cast<std::size_t>(i) * m.width;
  if (!detail::is_configuration(m, q)) {
    d_verdicts[i] = 1;  // no configuration: colliding, and no jobs
    return;
  }
  detail::Xf X_WL[detail::kMaxLinks];
  detail::link_poses(m, q, X_WL);
  auto emit = [&](int body, const detail::BodyRanges& r, const detail::Xf& X_AB, float threshold) {
    const unsigned slot = atomicAdd(&d_state->jobs, 1u);
    if (slot >= static_cast<unsigned>(job_capacity)) {
      d_state->jobs_overflow = 1;
      return;
    }
    Job job;
    job.query = i;
    job.body = body;
    job.threshold = threshold;
    job.a = r.a;
    job.b = r.b;
    store_transform(X_AB, job.X_AB);
    d_jobs[slot] = job;
    d_tasks[slot] = {static_cast<int>(slot), 0, 0};
  };
  const float* clearances = query_clearances(m, i);
  const auto pose = [&](int l) { return X_WL[l]; };
  const auto centre = [&](int l) { return detail::sphere_center_W(m, l, X_WL[l]); };
  for (int body = 0; body < detail::body_count(m); ++body) {
    const detail::BodyTolerance tolerance = detail::body_tolerance(m, body, clearances);
    if (detail::body_may_touch(m, body, centre, tolerance.margin)) {
      emit(body, detail::body_ranges(m, body), detail::body_transform(m, body, pose),
           tolerance.threshold);
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
// (measured: benchmarks/history/tuning_notes.md, "kWarpRootsUpTo").
constexpr int kRootWarps = 4;  // warps (queries) per block
constexpr std::size_t kWarpRootsUpTo = 16384;

__global__ void __launch_bounds__(32 * kRootWarps)
    balanced_roots_warp_kernel(CollisionModelView m, const float* d_q, int n, Job* d_jobs,
                               int job_capacity, Task* d_tasks, std::uint8_t* d_verdicts,
                               BalancedState* d_state) {
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
  const auto centre = [&](int l) {
    const float4 c = s_spheres[warp][l];
    return detail::V3f{c.x, c.y, c.z};
  };
  const auto pose = [&](int l) { return detail::load_transform(poses[l]); };
  const int bodies = detail::body_count(m);
  for (int start = 0; start < bodies; start += 32) {
    const int b = start + static_cast<int>(lane);
    const detail::BodyTolerance tolerance =
        detail::body_tolerance(m, b < bodies ? b : 0, query_clearances(m, i));
    const bool touch = b < bodies && detail::body_may_touch(m, b, centre, tolerance.margin);
    const unsigned touching = __ballot_sync(kFullMask, touch);
    if (touching == 0) continue;
    unsigned base = 0;
    const int leader = __ffs(touching) - 1;
    if (lane == static_cast<unsigned>(leader))
      base = atomicAdd(&d_state->jobs, static_cast<unsigned>(__popc(touching)));
    base = __shfl_sync(kFullMask, base, leader);
    if (!touch) continue;
    const unsigned slot = base + __popc(touching & ((1u << lane) - 1u));
    if (slot >= static_cast<unsigned>(job_capacity)) {
      d_state->jobs_overflow = 1;
      continue;
    }
    Job job;
    job.query = i;
    job.body = b;
    job.threshold = tolerance.threshold;
    const detail::BodyRanges r = detail::body_ranges(m, b);
    job.a = r.a;
    job.b = r.b;
    store_transform(detail::body_transform(m, b, pose), job.X_AB);
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
// kFinish: the same for what a traversal's rounds left in a short queue (BalancedState::
// finish), a warp per task from its node pair, instead of more rounds of a few tasks each,
// whose cost is their launches and dependent steps whatever their size.
template <bool kFinish>
__global__ void __launch_bounds__(32 * kPairWarps)
    balanced_warp_per_pair_kernel(CollisionModelView m, const Job* d_jobs, const Task* d_tasks,
                                  int stack_capacity, std::uint8_t* d_collided,
                                  BalancedState* d_state, DeviceTestCounts* d_counts) {
  extern __shared__ int2 s_stacks[];
  if (d_state->jobs_overflow) return;  // the host runs the chunk again, smaller
  if (kFinish && !d_state->finish) return;
  const unsigned jobs = kFinish ? d_state->top : d_state->jobs;
  const unsigned lane = threadIdx.x & 31;
  int2* stack = s_stacks + static_cast<std::size_t>(threadIdx.x / 32) * stack_capacity;
  volatile std::uint8_t* collided_flags = d_collided;
  detail::TraversalCounts counts;
  while (true) {
    unsigned j = 0;
    if (lane == 0) j = atomicAdd(&d_state->next_job, 1u);
    j = __shfl_sync(kFullMask, j, 0);
    if (j >= jobs) break;
    const Task task = kFinish ? d_tasks[j] : Task{static_cast<int>(j), 0, 0};
    const Job& job = d_jobs[task.job];
    const int query = job.query;
    if (__shfl_sync(kFullMask, lane == 0 ? collided_flags[query] : 0, 0)) continue;
    const BodyRange body_a = job.a, body_b = job.b;
    const float threshold = job.threshold, margin = 2 * threshold;
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
        if (detail::nodes_overlap(na, nb, X_AB, margin)) {
          if (na.is_leaf() && nb.is_leaf()) {
            ++counts.triangle_tests;
            hit = detail::leaf_collides(m.triangles[body_a.triangle_offset + na.triangle()],
                                        m.triangles[body_b.triangle_offset + nb.triangle()], X_AB,
                                        threshold);
          } else {
            // The split without split_pair's order of the children: the next step tests
            // them side by side anyway.
            detail::split_node_pair(pair.x, pair.y, na, nb, &first, &second);
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
  add_counts(counts, d_counts);
}

// Steps of depth-first traversal one task runs before it hands what is left of its
// stack back to the queue: short enough that the work of one hard query spreads over
// many threads in the next launch, long enough that a query finding a collision stops
// its own search early.
constexpr int kTaskSteps = 32;
// Threads per block of the task kernel, with kStackEntries stack entries each in shared
// memory (how many blocks an SM holds is set by the carve-out): the fastest measured
// (benchmarks/history/tuning_notes.md, "kTaskThreads").
constexpr int kTaskThreads = 128;
// A task whose stack fills hands it back before its steps are used up. 24 entries
// (25 KB a block) let six blocks share an SM's 164 KB of shared memory where the 33 that
// 32 steps can reach let four; few stacks grow that deep (measured:
// benchmarks/history/tuning_notes.md, "kStackEntries").
constexpr int kStackEntries = 24;
// Once a round has fewer tasks than kTailTasks the GPU has room to spare, and tasks run
// kTailSteps: the remaining hard queries spread over more threads sooner.
constexpr unsigned kTailTasks = 65536;
constexpr unsigned kTailSteps = 8;
// After two rounds, a queue of at most kFinishTasks tasks is finished by one launch of
// the small-batch kernel, a warp per task, instead of the rounds of a few tasks each
// that remained (measured: benchmarks/history/tuning_notes.md, "kFinishTasks").
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
                         const std::uint8_t* d_collided, BalancedState* d_state,
                         DeviceTestCounts* d_counts) {
  const unsigned count = d_state->launch;
  if (count == 0) return;  // the queue ran empty in an earlier round of this burst
  const Task* d_tasks = d_queue + d_state->begin;
  const unsigned lane = threadIdx.x & 31;
  detail::TraversalCounts counts;
  // Each step pops one pair and pushes at most two; a stack that reaches kStackEntries
  // is handed back. The stacks live in shared memory, entry k of all threads side by
  // side, so that a lane always meets the same bank whatever its depth: in local memory
  // they missed the L1 and stalled the warps on L2 (benchmarks/history/tuning_notes.md,
  // "Task stacks in shared memory").
  __shared__ int2 s_stacks[kStackEntries][kTaskThreads];
  int2* stack = &s_stacks[0][threadIdx.x];
  int top = 0, job_index = 0, query = 0;
  unsigned steps = 0;
  BodyRange body_a{}, body_b{};
  float margin = 0;
  detail::Xf X_AB{}, X_BA{};
  const unsigned max_steps = d_state->steps;
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
          base = atomicAdd(&d_state->fetched, static_cast<unsigned>(__popc(fetching)));
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
            margin = 2 * job.threshold;
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
        if (detail::nodes_overlap(na, nb, X_AB, margin)) {
          if (na.is_leaf() && nb.is_leaf()) {
            const unsigned slot = atomicAdd(&d_state->leaves, 1u);
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
      if (lane == 31) base = atomicAdd(&d_state->tasks, static_cast<unsigned>(total));
      base = __shfl_sync(kFullMask, base, 31);
      const unsigned at = base + offset - leaving;
      for (int k = 0; k < leaving; ++k) {
        const int2 pair = stack[k * kTaskThreads];
        d_children[at + k] = {job_index, pair.x, pair.y};
      }
    }
    if (hand_back) top = 0;
  }
  add_counts(counts, d_counts);
}

// The leaf pairs of a round, a thread each (grid-stride): the triangle test, marking the
// query when it collides. The same kernel moves the round's children into the queue
// where its tasks were taken from.
__global__ void __launch_bounds__(256, 2)
    balanced_leaf_kernel(CollisionModelView m, const Job* d_jobs, const Task* d_leaves,
                         unsigned leaf_capacity, const Task* d_children, Task* d_queue,
                         std::uint8_t* d_collided, BalancedState* d_state,
                         DeviceTestCounts* d_counts) {
  const unsigned leaves = min(d_state->leaves, leaf_capacity);
  const unsigned children = d_state->tasks;
  Task* d_to = d_queue + d_state->begin;
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
                                detail::load_transform(job.X_AB), job.threshold)) {
        d_collided[job.query] = 1;
      }
    }
  }
  add_counts(counts, d_counts);
}

// Ends a round: the children join the queue, and the next round takes the newest tasks
// (depth-first across rounds, which keeps the queue short), as many as leave room for
// their children.
__device__ void advance_queue(BalancedState& c, unsigned task_capacity, unsigned max_launch) {
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

__global__ void balanced_advance_kernel(BalancedState* d_state, unsigned task_capacity,
                                        unsigned max_launch) {
  advance_queue(*d_state, task_capacity, max_launch);
}

// Starts a chunk's traversal after the roots kernel: the jobs' root tasks fill the
// queue, as if a round at 0 had emitted them. When the jobs overflowed their buffer no
// round runs (the host sees the flag and runs the chunk again, smaller).
__global__ void balanced_start_kernel(BalancedState* d_state, unsigned task_capacity,
                                      unsigned max_launch) {
  BalancedState& c = *d_state;
  c.begin = 0;
  c.tasks = c.jobs_overflow ? 0 : c.jobs;
  c.rounds = 0;
  c.queue_full = 0;
  advance_queue(c, task_capacity, max_launch);
}

// After the traversal (beside it, on a stream of its own, for a small batch:
// enqueue_small), the containment step (detail::body_contained) of every job whose query
// no surface test has found colliding, in two kernels. The first walks the component
// trees, two threads a job, one for each direction (a component of A inside a solid of
// B, one of B inside a solid of A), on the job's own transform, and queues every point
// that lies in a solid's box; the second runs each queued point's three rays a thread
// each. Only jobs can hold a body inside another (a body inside another lies within its
// bounding volumes; query_contained asks the same broad phase). Measured (ncu, H200,
// MotionBenchMaker's box, 256 Panda configurations): a thread per query, its bodies and
// their points' rays one after another, took 0.76 ms, nine tenths of the call; a thread
// per job and direction 0.54 ms (link 6's 29 components, each point in an obstacle's box:
// 87 rays in a row); these two kernels 0.08 ms (0.046 with point_in_node_box). Points
// beyond the queue's capacity are tested where they are found. Launched only for models
// with solids on either side of some checked body.
constexpr int kContainedThreads = 128;

__global__ void __launch_bounds__(kContainedThreads)
    balanced_contained_kernel(CollisionModelView m, const Job* d_jobs, BalancedState* d_state,
                              PointInSolid* d_points, unsigned point_capacity,
                              std::uint8_t* d_verdicts) {
  if (d_state->jobs_overflow) return;  // the host runs the chunk again, smaller
  const unsigned t = blockIdx.x * blockDim.x + threadIdx.x;
  const unsigned j = t / 2;
  if (j >= d_state->jobs) return;
  const Job& job = d_jobs[j];
  if (d_verdicts[job.query]) return;
  const detail::BodySolidsPair s = detail::body_solids(m, job.body);
  const detail::Xf X_AB = detail::load_transform(job.X_AB);
  const float margin = 2 * job.threshold;  // body_tolerance's
  const auto queue = [&](int component, detail::V3d p) {
    const unsigned slot = atomicAdd(&d_state->points_in_solids, 1u);
    if (slot >= point_capacity)
      return detail::point_in_solid(m.solids, m.solids.components[component], p);
    d_points[slot] =
        PointInSolid{{static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)},
                     component,
                     job.query,
                     0u};
    return false;
  };
  const bool inside =
      (t & 1u)
          ? detail::components_inside_by(m.solids, s.a, s.b, geometry::inverse(X_AB), margin, queue)
          : detail::components_inside_by(m.solids, s.b, s.a, X_AB, margin, queue);
  if (inside) d_verdicts[job.query] = 1;
}

// The queued points' rays, a thread each (grid-stride over the count on the device); the
// last of a point's three rays to finish applies the vote.
__global__ void balanced_point_rays_kernel(CollisionModelView m, const BalancedState* d_state,
                                           PointInSolid* d_points, unsigned point_capacity,
                                           std::uint8_t* d_verdicts) {
  if (d_state->jobs_overflow) return;
  const unsigned rays = 3 * min(d_state->points_in_solids, point_capacity);
  for (unsigned t = blockIdx.x * blockDim.x + threadIdx.x; t < rays; t += gridDim.x * blockDim.x) {
    PointInSolid& point = d_points[t / 3];
    if (d_verdicts[point.query]) continue;
    const detail::V3d p{point.p[0], point.p[1], point.p[2]};
    const bool inside = detail::ray_winding(m.solids, m.solids.components[point.component], p,
                                            detail::containment_ray(static_cast<int>(t % 3))) != 0;
    const unsigned tally =
        atomicAdd(&point.tally, inside ? 0x101u : 0x1u) + (inside ? 0x101u : 0x1u);
    if ((tally & 0xffu) == 3 && (tally >> 8) >= 2) d_verdicts[point.query] = 1;
  }
}
}  // namespace

void BalancedTraversal::run_containment(const CollisionModelView& m, std::size_t jobs,
                                        std::uint8_t* d_verdicts, cudaStream_t stream) {
  if (!m.containment || jobs == 0) return;
  const unsigned capacity = static_cast<unsigned>(point_capacity_);
  balanced_contained_kernel<<<blocks_for(2 * jobs, kContainedThreads), kContainedThreads, 0,
                              stream>>>(m, jobs_.get(), state_.get(), points_.get(), capacity,
                                        d_verdicts);
  balanced_point_rays_kernel<<<resident_ray_blocks_, kContainedThreads, 0, stream>>>(
      m, state_.get(), points_.get(), capacity, d_verdicts);
  check_cuda(cudaGetLastError(), "balanced containment kernels");
}

BalancedTraversal::BalancedTraversal(const FlatCollisionModel& host,
                                     const cudaDeviceProp& properties) {
  int blocks_per_sm = 0;
  // The shared-memory share of the SM's 256 KB of L1 and shared memory that the task
  // kernel asks for, in percent of the largest (the driver rounds it to a size the SM
  // has): 60, the fastest measured (benchmarks/history/tuning_notes.md, "Shared-memory
  // carve-out"); with 24-entry stacks it holds six blocks.
  check_cuda(cudaFuncSetAttribute(balanced_task_kernel,
                                  cudaFuncAttributePreferredSharedMemoryCarveout, 60),
             "carve-out");
  check_cuda(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&blocks_per_sm, balanced_task_kernel,
                                                           kTaskThreads, 0),
             "occupancy");
  resident_task_blocks_ = std::max(1, blocks_per_sm) * properties.multiProcessorCount;
  check_cuda(
      cudaOccupancyMaxActiveBlocksPerMultiprocessor(&blocks_per_sm, balanced_leaf_kernel, 256, 0),
      "occupancy");
  resident_leaf_blocks_ = std::max(1, blocks_per_sm) * properties.multiProcessorCount;

  bodies_ = static_cast<std::size_t>(detail::body_count(host.view()));
  many_bodies_ = bodies_ > 32;
  pair_stack_capacity_ = 64 * (host.traversal_depth + 1);
  const std::size_t stack_bytes = pair_stack_capacity_ * sizeof(int2);  // at most 66 KB
  pair_warps_ = static_cast<int>(
      std::clamp<std::size_t>(properties.sharedMemPerBlockOptin / stack_bytes, 1, kPairWarps));
  pair_shared_bytes_ = pair_warps_ * stack_bytes;
  for (auto* kernel : {balanced_warp_per_pair_kernel<false>, balanced_warp_per_pair_kernel<true>})
    check_cuda(cudaFuncSetAttribute(kernel, cudaFuncAttributeMaxDynamicSharedMemorySize,
                                    static_cast<int>(pair_shared_bytes_)),
               "shared memory of the small-batch kernel");
  check_cuda(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&blocks_per_sm,
                                                           balanced_warp_per_pair_kernel<false>,
                                                           32 * pair_warps_, pair_shared_bytes_),
             "occupancy");
  pair_blocks_ = std::max(1, blocks_per_sm) * properties.multiProcessorCount;
  check_cuda(cudaOccupancyMaxActiveBlocksPerMultiprocessor(
                 &blocks_per_sm, balanced_point_rays_kernel, kContainedThreads, 0),
             "occupancy");
  resident_ray_blocks_ = std::max(1, blocks_per_sm) * properties.multiProcessorCount;
  state_.reserve(1);
}

void BalancedTraversal::reserve(std::size_t chunk, std::size_t memory_cap) {
  // Shares of the memory cap, each also bounded outright (16M jobs, 128M queued tasks:
  // far above what the shipped scenes reach) so that a large free memory is not claimed
  // for nothing. A chunk whose jobs overflow is rerun at half the size.
  job_capacity_ =
      std::min({chunk * bodies_, static_cast<std::size_t>(0.3 * memory_cap) / sizeof(Job),
                std::size_t(1) << 24});
  task_capacity_ = std::max<std::size_t>(
      2 * job_capacity_ + 4 * kStackEntries,
      std::min(static_cast<std::size_t>(0.25 * memory_cap) / sizeof(Task), std::size_t(1) << 27));
  jobs_.reserve(job_capacity_);
  tasks_.reserve(task_capacity_);
  children_capacity_ = std::min<std::size_t>(task_capacity_, std::size_t(kStackEntries) << 20);
  children_.reserve(children_capacity_);
  leaf_capacity_ = std::max<std::size_t>(
      1024, std::min<std::size_t>(std::size_t(1) << 22,
                                  static_cast<std::size_t>(0.05 * memory_cap) / sizeof(Task)));
  leaves_.reserve(leaf_capacity_);
  point_capacity_ =
      std::clamp<std::size_t>(static_cast<std::size_t>(0.02 * memory_cap) / sizeof(PointInSolid),
                              1024, std::size_t(1) << 18);
  points_.reserve(point_capacity_);
}

BalancedState BalancedTraversal::read_state() {
  BalancedState c;
  check_cuda(cudaMemcpy(&c, state_.get(), sizeof(c), cudaMemcpyDeviceToHost), "read counters");
  return c;
}

void BalancedTraversal::launch_roots(const CollisionModelView& m, const float* d_q, int n,
                                     std::uint8_t* d_verdicts, GpuCheckStats* stats) {
  const bool warp_roots = many_bodies_ && static_cast<std::size_t>(n) <= kWarpRootsUpTo;
  if (warp_roots) {
    balanced_roots_warp_kernel<<<blocks_for(n, kRootWarps), 32 * kRootWarps>>>(
        m, d_q, n, jobs_.get(), static_cast<int>(job_capacity_), tasks_.get(), d_verdicts,
        state_.get());
  } else {
    balanced_roots_kernel<<<blocks_for(n, 128), 128>>>(m, d_q, n, jobs_.get(),
                                                       static_cast<int>(job_capacity_),
                                                       tasks_.get(), d_verdicts, state_.get());
  }
  check_cuda(cudaGetLastError(), "balanced roots kernel");
  stats->root_lanes = warp_roots ? 32 : 1;
}

std::size_t BalancedTraversal::small_batch_up_to(std::size_t warp_per_pair_up_to) const {
  if (warp_per_pair_up_to != GpuCheckerOptions::kAuto) return warp_per_pair_up_to;
  if (!many_bodies_) return 10;
  // Up to 4,096 queries of a robot with up to 40 bodies, 1,024 of one with 160 or more,
  // between them in proportion (the jobs a warp takes in turn). Measured (H200, gplan
  // check, uniform samples): the Panda's 34 bodies on MotionBenchMaker's box, cage and
  // bookshelf, 2,048 queries 0.49 to 0.37 ms, 4,096 0.60 to 0.48 ms, 8,192 from 0.75
  // ms faster to 0.08 ms slower, 16,384 slower; the PR2 arm and the humanoid (hundreds of
  // bodies) keep issue 4's 1,024.
  constexpr std::size_t kBodyQueries = 4096 * 40;
  return std::clamp<std::size_t>(kBodyQueries / bodies_, 1024, 4096);
}

void BalancedTraversal::enqueue_small(const CollisionModelView& m, const float* d_q, int n,
                                      std::uint8_t* d_verdicts, DeviceTestCounts* d_counts,
                                      BalancedState* h_state) {
  check_cuda(cudaMemsetAsync(state_.get(), 0, sizeof(BalancedState)), "memset");
  check_cuda(cudaMemsetAsync(d_verdicts, 0, n), "memset");
  GpuCheckStats unused;
  launch_roots(m, d_q, n, d_verdicts, &unused);
  // The containment step beside the traversal: both need only the roots' jobs, and a
  // small batch leaves most of the device idle while its longest traversals finish (the
  // step's walk took 20 to 90 us of a 150 to 400 us call of MotionBenchMaker's Panda).
  // It skips the queries the traversal has found colliding by then, no longer all of
  // them; both only ever set a verdict. After an overflow the verdicts are thrown away
  // anyway. The jobs are counted on the device: threads for as many as the batch can have.
  const bool containment = m.containment;
  if (containment) {
    check_cuda(cudaEventRecord(roots_done_.get(), 0), "event");
    check_cuda(cudaStreamWaitEvent(containment_stream_.get(), roots_done_.get(), 0), "wait");
    run_containment(m, std::min(static_cast<std::size_t>(n) * bodies_, job_capacity_), d_verdicts,
                    containment_stream_.get());
    check_cuda(cudaEventRecord(containment_done_.get(), containment_stream_.get()), "event");
  }
  balanced_warp_per_pair_kernel<false><<<pair_blocks_, 32 * pair_warps_, pair_shared_bytes_>>>(
      m, jobs_.get(), nullptr, pair_stack_capacity_, d_verdicts, state_.get(), d_counts);
  check_cuda(cudaGetLastError(), "balanced small-batch kernel");
  if (containment) check_cuda(cudaStreamWaitEvent(0, containment_done_.get(), 0), "wait");
  check_cuda(cudaMemcpyAsync(h_state, state_.get(), sizeof(BalancedState), cudaMemcpyDeviceToHost),
             "read counters");
}

bool BalancedTraversal::finish_small(const BalancedState& h_state, GpuCheckStats* stats) const {
  if (h_state.jobs_overflow) return false;
  stats->root_lanes = many_bodies_ ? 32 : 1;
  stats->warp_per_pair = true;
  stats->jobs += h_state.jobs;
  return true;
}

bool BalancedTraversal::run(const CollisionModelView& m, const float* d_q, int n,
                            std::uint8_t* d_verdicts, DeviceTestCounts* d_counts,
                            std::size_t warp_per_pair_up_to, GpuCheckStats* stats) {
  check_cuda(cudaMemsetAsync(state_.get(), 0, sizeof(BalancedState)), "memset");
  check_cuda(cudaMemset(d_verdicts, 0, n), "memset");
  launch_roots(m, d_q, n, d_verdicts, stats);
  if (static_cast<std::size_t>(n) <= small_batch_up_to(warp_per_pair_up_to)) {
    balanced_warp_per_pair_kernel<false><<<pair_blocks_, 32 * pair_warps_, pair_shared_bytes_>>>(
        m, jobs_.get(), nullptr, pair_stack_capacity_, d_verdicts, state_.get(), d_counts);
    check_cuda(cudaGetLastError(), "balanced small-batch kernel");
    stats->warp_per_pair = true;
    const BalancedState c = read_state();
    if (c.jobs_overflow) return false;
    run_containment(m, c.jobs, d_verdicts);
    stats->jobs += c.jobs;
    return true;
  }
  // Each task may leave up to kStackEntries node pairs behind.
  const unsigned max_launch =
      static_cast<unsigned>(std::min<std::size_t>(1u << 20, children_capacity_ / kStackEntries));
  const unsigned capacity = static_cast<unsigned>(std::min<std::size_t>(task_capacity_, ~0u));
  balanced_start_kernel<<<1, 1>>>(state_.get(), capacity, max_launch);
  BalancedState c;
  // Rounds run in bursts without the host; the queue is read between bursts, and a
  // round after the queue ran empty costs three near-empty launches.
  const int burst = 4;
  while (true) {
    for (int r = 0; r < burst; ++r) {
      balanced_task_kernel<<<resident_task_blocks_, kTaskThreads>>>(
          m, jobs_.get(), tasks_.get(), children_.get(), leaves_.get(),
          static_cast<unsigned>(leaf_capacity_), d_verdicts, state_.get(), d_counts);
      balanced_leaf_kernel<<<resident_leaf_blocks_, 256>>>(
          m, jobs_.get(), leaves_.get(), static_cast<unsigned>(leaf_capacity_), children_.get(),
          tasks_.get(), d_verdicts, state_.get(), d_counts);
      balanced_advance_kernel<<<1, 1>>>(state_.get(), capacity, max_launch);
    }
    // Nothing to do unless a round left a short queue (then the rounds above it did
    // nothing either).
    balanced_warp_per_pair_kernel<true><<<pair_blocks_, 32 * pair_warps_, pair_shared_bytes_>>>(
        m, jobs_.get(), tasks_.get(), pair_stack_capacity_, d_verdicts, state_.get(), d_counts);
    check_cuda(cudaGetLastError(), "balanced traversal kernels");
    c = read_state();
    if (c.jobs_overflow) return false;
    if (c.queue_full)
      throw std::runtime_error("balanced traversal: task queue full; lower the batch size");
    if (c.finish || c.top == 0) break;
  }
  run_containment(m, c.jobs, d_verdicts);
  stats->rounds += c.rounds;
  stats->jobs += c.jobs;
  if (c.finish) stats->finished_tasks += c.top;
  for (unsigned r = 0; r < std::min<unsigned>(c.rounds, kTracedRounds); ++r)
    stats->round_tasks.push_back(c.round_tasks[r]);
  return true;
}

}  // namespace gplanner::traversals
