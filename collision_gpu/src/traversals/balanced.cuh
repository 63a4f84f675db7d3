#pragma once
// The `balanced` traversal, the seed's workload-balanced one: every body pair of every
// query that survives the broad phase becomes a job; the node pairs of the jobs' BVTTs
// are tasks in a global queue, run in rounds of launches in which every lane takes
// tasks in turn, tests up to a few dozen node pairs depth-first and hands what is left
// back to the queue, so that the work of hard queries spreads over the whole GPU. Small
// batches, and the short queue the rounds leave, are finished a warp per task instead.

#include <cuda_runtime.h>

#include <cstddef>
#include <cstdint>

#include "gplanner/collision_gpu/gpu_batch_checker.h"
#include "gplanner/collision_gpu/model_view.h"
#include "traversals/traversal_common.cuh"

namespace gplanner::traversals {

// One body pair of one query that survived the broad phase: the unit tasks refer to.
// Its leaf threshold: the model's, or a clearance's (detail::body_tolerance; the BV margin
// is twice it).
struct alignas(16) Job {
  int query;
  int body;  // numbered as detail::body_count's
  float threshold;
  BodyRange a, b;
  float X_AB[12];
};

// A node pair of a job: an inner pair to traverse, or (in the leaf queue) two leaves
// whose triangles to test.
struct Task {
  int job, a, b;
};

// A point of one body in a solid component's box of the other, found by the containment
// step's walk (detail::components_inside_by): its three rays run a thread each, and
// the two of three that agree decide (detail::point_in_solid's vote).
struct alignas(16) PointInSolid {
  float p[3];     // in the solid's body frame
  int component;  // the solid, in SolidsView::components
  int query;
  unsigned tally;  // rays done (low byte) and rays that found the point inside (above it)
};

constexpr int kTracedRounds = 32;

// The traversal's counters and the state of its task queue, on the device, so that
// rounds follow one another without the host. Counters that many threads add to at once
// each sit on a cache line of their own: on one line their atomics queued behind each
// other at the same L2 slice (measured: benchmarks/history/tuning_notes.md,
// "BalancedState's cache lines").
struct alignas(128) BalancedState {
  unsigned int jobs;  // jobs emitted
  unsigned int jobs_overflow;
  unsigned int next_job;  // small batches: jobs taken by warps
  // Tasks [0, top) are queued; a round takes [begin, begin + launch).
  alignas(128) unsigned int top, begin, launch;
  alignas(128) unsigned int tasks;    // children emitted by this round's task kernel
  alignas(128) unsigned int leaves;   // leaf pairs emitted by this round's task kernel
  alignas(128) unsigned int fetched;  // tasks taken by the lanes of this round's task kernel
  alignas(128) unsigned int rounds;   // rounds that had tasks
  unsigned int steps;                 // BV tests a task of this round runs at most
  unsigned int queue_full;
  unsigned int finish;                      // the queue is short: the finish kernel takes all of it
  alignas(128) unsigned int points_in_solids;  // PointInSolid tests queued (beyond capacity: run at
                                               // once)
  unsigned int round_tasks[kTracedRounds];  // tasks each of the first rounds took
};

class BalancedTraversal {
 public:
  // The share of the memory cap that a chunk's configurations and verdicts take; the
  // queues take most of the rest.
  static constexpr double kChunkShare = 0.1;

  // Sets the kernels' shared memory and finds how many blocks of each fit on the device.
  BalancedTraversal(const FlatCollisionModel& host, const cudaDeviceProp& properties);

  // Sizes the job and task queues for chunks of up to `chunk` queries within memory_cap
  // bytes.
  void reserve(std::size_t chunk, std::size_t memory_cap);

  // d_q: device, shape [n, m.width]; d_verdicts: device, shape [n] (1: collision).
  // warp_per_pair_up_to: GpuCheckerOptions's. Adds rounds, jobs and tasks to *stats.
  // Returns false when the chunk's jobs overflowed their queue: run it again, smaller.
  bool run(const CollisionModelView& m, const float* d_q, int n, std::uint8_t* d_verdicts,
           DeviceTestCounts* d_counts, std::size_t warp_per_pair_up_to, GpuCheckStats* stats);

  // Batches of up to this many queries run in one kernel, a warp per body pair, no rounds.
  std::size_t small_batch_up_to(std::size_t warp_per_pair_up_to) const;
  // A small batch (n <= small_batch_up_to) with no host round trip: every step queued on
  // the default stream, the traversal's state copied to h_state (page-locked) at the end.
  // After the stream has been synchronised, finish_small() reads it: false when the jobs
  // overflowed their queue (run the batch again with run()).
  void enqueue_small(const CollisionModelView& m, const float* d_q, int n, std::uint8_t* d_verdicts,
                     DeviceTestCounts* d_counts, BalancedState* h_state);
  bool finish_small(const BalancedState& h_state, GpuCheckStats* stats) const;

 private:
  BalancedState read_state();
  // The kinematics and broad-phase kernel that makes a batch's jobs.
  void launch_roots(const CollisionModelView& m, const float* d_q, int n, std::uint8_t* d_verdicts,
                    GpuCheckStats* stats);
  // The containment step of the jobs whose queries the traversal left free; `jobs`: at
  // least the jobs emitted (the kernel reads their count on the device); on `stream`.
  void run_containment(const CollisionModelView& m, std::size_t jobs, std::uint8_t* d_verdicts,
                       cudaStream_t stream = 0);

  int resident_task_blocks_ = 1;  // blocks of each kernel resident at once
  int resident_leaf_blocks_ = 1;
  // Whether a query has more link and pair sphere tests than a warp has lanes; then
  // batches of up to kWarpRootsUpTo queries run kinematics and broad phase a warp per
  // query.
  bool many_bodies_ = false;
  std::size_t bodies_ = 0;             // checked bodies per query: links and link pairs
  int pair_stack_capacity_ = 0;        // small batches: node pairs per warp's stack
  int pair_warps_ = 1;                 // warps (stacks) per block of the small-batch kernel
  int pair_blocks_ = 1;                // resident blocks of the small-batch kernel
  std::size_t pair_shared_bytes_ = 0;  // its dynamic shared memory: pair_warps_ stacks
  std::size_t job_capacity_ = 0, task_capacity_ = 0, children_capacity_ = 0, leaf_capacity_ = 0;
  std::size_t point_capacity_ = 0;
  int resident_ray_blocks_ = 1;

  // A small batch's containment step runs on a stream of its own beside the traversal,
  // from the roots kernel's end (roots_done_) to its own (containment_done_), for which
  // the default stream waits.
  cuda::Stream containment_stream_;
  cuda::Event roots_done_{cudaEventDisableTiming}, containment_done_{cudaEventDisableTiming};

  cuda::DeviceBuffer<BalancedState> state_;
  cuda::DeviceBuffer<Job> jobs_;
  cuda::DeviceBuffer<Task> tasks_, children_, leaves_;
  cuda::DeviceBuffer<PointInSolid> points_;
};

}  // namespace gplanner::traversals
