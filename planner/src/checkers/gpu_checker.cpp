#include "gplanner/planner/checkers/gpu_checker.h"

#include <algorithm>
#include <chrono>
#include <random>

#include "gplanner/common/parallel_for.h"
#include "gplanner/planner/scene/scene_collision_model.h"

namespace gplanner {
namespace {

// The fastest of `repeats` runs of f, in seconds: a call's cost without the noise of
// other work on the machine.
template <typename F>
double fastest_seconds(int repeats, F&& f) {
  double best = 1e30;
  for (int r = 0; r < repeats; ++r) {
    const auto started = std::chrono::steady_clock::now();
    f();
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  }
  return best;
}

// seconds[i] measured at sizes[i] (increasing), read at n: linear between the two
// measured sizes around n, the nearest measurement's per-configuration cost beyond them.
double interpolate(const std::vector<std::size_t>& sizes, const std::vector<double>& seconds,
                   std::size_t n) {
  if (n <= sizes.front()) return seconds.front();
  for (std::size_t i = 1; i < sizes.size(); ++i) {
    if (n <= sizes[i]) {
      const double t = double(n - sizes[i - 1]) / double(sizes[i] - sizes[i - 1]);
      return seconds[i - 1] + t * (seconds[i] - seconds[i - 1]);
    }
  }
  return seconds.back() * double(n) / double(sizes.back());
}

}  // namespace

GpuChecker::GpuChecker(const Scene& scene, const GpuCheckerOptions& options, int host_threads)
    : GpuChecker(build_collision_model(scene), scene, options, host_threads) {}

GpuChecker::GpuChecker(const CollisionModel& model, const Scene& scene,
                       const GpuCheckerOptions& options, int host_threads)
    : traversal_(options.traversal),
      gpu_(model, options),
      host_(model, host_threads),
      host_threads_(resolve_thread_count(host_threads)) {
  if (options.host_calls_up_to == GpuCheckerOptions::kAuto) {
    measure_routing(scene);
  } else {
    // Up to the given size on the host: calls of up to 4 configurations on the calling
    // thread (where the pool's helpers would take longer to wake than to help).
    routing_.calling_thread_up_to = std::min<std::size_t>(options.host_calls_up_to, 4);
    routing_.host_threads_up_to = options.host_calls_up_to;
  }
}

GpuChecker::~GpuChecker() = default;

void GpuChecker::measure_routing(const Scene& scene) {
  // The scene's free uniform samples stand for the planner's checks, most of which are
  // of free configurations (the samples of motions that pass, their fine checks, their
  // certification): a colliding one ends at its first collision, and costs the host
  // less. Measured on MotionBenchMaker's Panda (H200), calls of 4 to 16 free samples of
  // a plan's motions took the host 0.1 to 0.4 ms, the GPU 0.1 ms. Where no sample is
  // free, all of them.
  const std::size_t width = scene.space.width();
  const std::vector<std::size_t> sizes = {1, 4, 16, 64, 256, 1024, 4096};
  const std::size_t most = 2 * sizes.back();
  std::vector<float> q(most * width);
  std::mt19937_64 rng(1);
  for (std::size_t i = 0; i < most; ++i) scene.space.sample_uniform(&rng, &q[i * width]);
  std::vector<std::uint8_t> verdicts(most);
  HostCallRouting& r = routing_;
  r.measured = true;
  r.sizes = sizes;
  gpu_.check(q.data(), most, verdicts.data());  // warm-up (first launches, caches); free?
  std::vector<float> free_rows;
  for (std::size_t i = 0; i < most; ++i)
    if (!verdicts[i]) free_rows.insert(free_rows.end(), &q[i * width], &q[(i + 1) * width]);
  if (!free_rows.empty()) {
    for (std::size_t i = 0; i < most; ++i)  // the free rows over and over
      std::copy_n(&free_rows[i * width % free_rows.size()], width, &q[i * width]);
  }
  gpu_.check(q.data(), sizes.back(), verdicts.data());
  // The median of five calls, each on other rows: a few hard configurations make a small
  // call's cost, so one set of rows would say little.
  const auto median_of_calls = [&](std::size_t n, auto&& call) {
    std::vector<double> seconds;
    for (std::size_t k = 0; k < 5; ++k) {
      const float* rows = q.data() + (k * n) % (most - n + 1) * width;
      seconds.push_back(fastest_seconds(1, [&] { call(rows, n); }));
    }
    std::nth_element(seconds.begin(), seconds.begin() + 2, seconds.end());
    return seconds[2];
  };
  // One host thread: 256 states.
  const std::size_t host_sample = 256;
  r.host_seconds_per_configuration =
      fastest_seconds(1, [&] { host_.check(q.data(), host_sample, verdicts.data(), nullptr, 1); }) /
      host_sample;
  // Each way timed alike, on the same rows; once the pool is twice as slow as the GPU,
  // or the calling thread twice as slow as the faster of them, larger calls are not timed
  // there.
  bool pool_still_competes = true, calling_thread_still_competes = true;
  const auto on_host = [&](int threads) {
    return [&, threads](const float* rows, std::size_t m) {
      host_.check(rows, m, verdicts.data(), nullptr, threads);
    };
  };
  for (const std::size_t n : sizes) {
    r.gpu_seconds.push_back(median_of_calls(
        n, [&](const float* rows, std::size_t m) { gpu_.check(rows, m, verdicts.data()); }));
    r.host_threads_seconds.push_back(
        pool_still_competes ? median_of_calls(n, on_host(host_threads_)) : 1e30);
    r.calling_thread_seconds.push_back(
        calling_thread_still_competes ? median_of_calls(n, on_host(1)) : 1e30);
    const double faster = std::min(r.gpu_seconds.back(), r.host_threads_seconds.back());
    pool_still_competes = r.host_threads_seconds.back() < 2 * r.gpu_seconds.back();
    calling_thread_still_competes = r.calling_thread_seconds.back() < 2 * faster;
  }
  // The host while it beats the GPU, from the smallest call up (powers of two); on the
  // calling thread while it beats the pool (whose calls of a few configurations still
  // pay for waking helpers), larger calls on the pool.
  const auto calling_thread = [&](std::size_t n) {
    return interpolate(sizes, r.calling_thread_seconds, n);
  };
  const auto pool = [&](std::size_t n) { return interpolate(sizes, r.host_threads_seconds, n); };
  const auto gpu = [&](std::size_t n) { return interpolate(sizes, r.gpu_seconds, n); };
  for (std::size_t n = 1; n <= sizes.back() && std::min(calling_thread(n), pool(n)) <= gpu(n);
       n *= 2)
    r.host_threads_up_to = n;
  for (std::size_t n = 1; n <= r.host_threads_up_to && calling_thread(n) <= pool(n); n *= 2)
    r.calling_thread_up_to = n;
  // The call's fixed cost over one configuration's: sizes 1, 1,024 and 4,096, where the
  // cost has grown linear.
  const double fixed = r.gpu_seconds.front();
  const double per_configuration = (gpu(4096) - gpu(1024)) / (4096 - 1024);
  r.call_cost =
      per_configuration > 0
          ? static_cast<std::size_t>(std::clamp(fixed / per_configuration, 256.0, 65536.0))
          : 65536;
}

std::size_t GpuChecker::host_calls_up_to() const {
  const HostCallRouting& r = routing_;
  if (!r.measured) return r.host_threads_up_to;
  const double ratio = host_cost_ratio();
  // One configuration stays where the measurement put it, whatever the ratio: its calls
  // keep the ratio current.
  std::size_t up_to = std::min<std::size_t>(1, r.host_threads_up_to);
  for (std::size_t n = 2; n <= r.host_threads_up_to; n *= 2) {
    const double host = std::min(interpolate(r.sizes, r.calling_thread_seconds, n),
                                 interpolate(r.sizes, r.host_threads_seconds, n));
    if (host * ratio > interpolate(r.sizes, r.gpu_seconds, n)) break;
    up_to = n;
  }
  return up_to;
}

void GpuChecker::route(const float* configurations, std::size_t n, const float* clearances,
                       std::uint8_t* verdicts) {
  if (n <= host_calls_up_to()) {
    check_on_host(configurations, n, clearances, verdicts);
  } else {
    ++device_calls_;
    gpu_.check(configurations, n, verdicts, clearances);
  }
}

void GpuChecker::check_on_host(const float* configurations, std::size_t n,
                               const float* clearances, std::uint8_t* verdicts) {
  const bool calling_thread = n <= routing_.calling_thread_up_to;
  const auto started = std::chrono::steady_clock::now();
  host_.check(configurations, n, verdicts, clearances, calling_thread ? 1 : host_threads_);
  // The call's time against the measured one of its size and way: a running mean (a
  // quarter the new call's) of their ratio, within [1/4, 1,000]. Sizes beyond the
  // routing's (host_checker()'s large calls) and calls with clearances (which cost more
  // by their clearances, not by where they lie) say nothing of it.
  const HostCallRouting& r = routing_;
  if (!r.measured || clearances != nullptr || n > r.host_threads_up_to) return;
  const double measured =
      interpolate(r.sizes, calling_thread ? r.calling_thread_seconds : r.host_threads_seconds, n);
  if (!(measured > 0 && measured < 1e29)) return;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const double ratio = 0.75 * host_cost_ratio() + 0.25 * (seconds / measured);
  host_cost_ratio_.store(std::clamp(ratio, 0.25, 1000.0), std::memory_order_relaxed);
}

void GpuChecker::check(const float* configurations, std::size_t n, std::uint8_t* verdicts) {
  route(configurations, n, nullptr, verdicts);
}

void GpuChecker::check_clearances(const float* configurations, std::size_t n,
                                  const float* clearances, std::uint8_t* verdicts) {
  route(configurations, n, clearances, verdicts);
}

}  // namespace gplanner
