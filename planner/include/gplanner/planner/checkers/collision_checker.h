#pragma once
// The batch call every backend answers: configurations in, one verdict each out.
//
// Threads: every backend takes calls of check() from any number of threads at once, a
// checker shared by them all (OMPL calls validity checkers from several). A call's
// verdicts are what it would get alone. The fcl and cpu backends run concurrent calls in
// parallel (per-call scratch, no lock around the work); the gpu backend runs one call's
// device work at a time. Statistics a backend keeps (bv_tests(), last_stats()) are those
// of the last call to finish, whole.

#include <cstddef>
#include <cstdint>
#include <string>

namespace gplanner {

struct Scene;

class CollisionChecker {
 public:
  virtual ~CollisionChecker() = default;

  // The backend that actually runs ("fcl", "cpu", "gpu").
  virtual std::string backend() const = 0;

  // configurations: shape [n, width], row-major; verdicts: shape [n], 1 when the
  // configuration collides (with the environment or itself), 0 when it is free.
  // n = 0 is answered without reading either pointer. Rows are checked as given: a
  // joint beyond its limits or a base outside the bounds is checked where it puts
  // the robot (the geometric verdict, as FCL gives it); keeping rows within bounds is
  // the caller's part (the OMPL validity checker reports such states invalid). A
  // quaternion of any finite non-zero length means its rotation. A row that is no
  // configuration (a NaN or infinite entry, a zero quaternion) is reported colliding
  // on every backend: never free, and no exception in the middle of a batch.
  virtual void check(const float* configurations, std::size_t n, std::uint8_t* verdicts) = 0;

  // As check(), with every checked pair held to a clearance, up to the tolerance band as
  // check() is: 1 also where link l comes closer to the environment than c_l metres, or
  // a checked link pair (a, b) closer to each other than c_a + c_b - 2 c_h, h being the
  // deepest link both hang from (RobotModel::deepest_common_link). clearances: shape [n,
  // robot links], per row c_l >= 0 and never smaller than the parent link's; a
  // clearance that is not a number makes its configuration colliding. What certified
  // motions rest on (planner/planning/certified_motions.h: c_l bounds how far link l's
  // points move, so c_a - c_h bounds how far a's move relative to h).
  virtual void check_clearances(const float* configurations, std::size_t n, const float* clearances,
                                std::uint8_t* verdicts) = 0;

  // About how many configurations cost as much to check as one call costs by itself:
  // callers that can check more configurations in fewer calls do so while the extra
  // configurations number fewer than this. 0 for the CPU backends (a call costs little
  // beside its configurations).
  virtual std::size_t configurations_per_call_cost() const { return 0; }
  // Calls of up to this many configurations cost about their configurations alone, no
  // fixed cost per call (answered on the calling thread, or by host threads that are
  // already running): callers that can find a collision after checking a few
  // configurations (a motion's samples, coarse to fine) check them a few at a time up to
  // this size, stopping at the first collision. The CPU backends: every size.
  virtual std::size_t cheap_calls_up_to() const { return ~std::size_t(0); }
  // The same checks answered on the host whatever their size, never in a GPU call: on
  // the calling thread, and on the thread pool where the checker measured that the pool
  // is faster. For a caller that checks a few configurations at a time and stops early,
  // where a GPU call's fixed cost would not pay. The CPU backends: themselves.
  virtual CollisionChecker* host_checker() { return this; }
  // GPU calls made so far by this checker, on all threads (a call of check() that the
  // gpu backend answers on the host is none): what a planner reports per stage, as the
  // difference before and after it. The CPU backends: 0.
  virtual std::size_t device_calls() const { return 0; }
  // The CUDA device its GPU calls run on (the first of several), -1 for the CPU
  // backends: where a planner puts its other GPU work (the k-NN search).
  virtual int gpu_device() const { return -1; }
  bool in_collision(const float* configuration) {
    std::uint8_t verdict = 0;
    check(configuration, 1, &verdict);
    return verdict != 0;
  }
};

// Throws InputError naming the scene file, line and key when start or goal collides.
void check_start_and_goal(const Scene& scene, CollisionChecker* checker);

// The first fraction t in (0, 1) of the way from start to goal (sampled every
// `step` of the way, all samples in one batch) at which the straight line collides;
// a negative value when every sample is free.
double first_collision_on_straight_line(const Scene& scene, CollisionChecker* checker,
                                        double step = 0.001);

}  // namespace gplanner
