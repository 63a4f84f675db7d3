// k-NN benchmark: 100,000 piano milestones (a floating base: positions uniform in a
// 10 x 8 x 3 m box, rotations uniform on SO(3), weights 1), k = 15. Times the GPU
// all-points search (median of several runs after a warm-up), the CPU reference on all
// hardware threads, and OMPL's NearestNeighborsGNAT with the same metric (built, then
// queried for every milestone on one thread, as OMPL's planners use it), and prints one
// JSON line with the times, their ratios, and how often the neighbour sets agree.
// With --arm J: milestones of an arm of J revolute joints instead (no base, each joint
// uniform in [-2.9, 2.9] rad, as the Panda's roadmaps), for the sizes a plan's first
// rounds have (--points 2002: the first round's k-NN).
//
// usage: gplanner_knn_bench [--points N] [--k K] [--runs R] [--seed S] [--no-cpu]
//                           [--no-gnat] [--arm J]

#include <ompl/datastructures/NearestNeighborsGNAT.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iostream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "gplanner/common/parallel_for.h"
#include "gplanner/knn_gpu/nearest_neighbors.h"

namespace {

using gplanner::ConfigurationMetric;
using gplanner::NeighborTable;

struct Options {
  std::size_t points = 100000;
  int k = 15;
  int runs = 7;
  unsigned seed = 2024;
  bool cpu = true;
  bool gnat = true;
  int arm_joints = 0;  // 0: the piano
};

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--points") {
      options.points = std::stoul(value());
    } else if (arg == "--k") {
      options.k = std::stoi(value());
    } else if (arg == "--runs") {
      options.runs = std::max(1, std::stoi(value()));
    } else if (arg == "--seed") {
      options.seed = static_cast<unsigned>(std::stoul(value()));
    } else if (arg == "--no-cpu") {
      options.cpu = false;
    } else if (arg == "--arm") {
      options.arm_joints = std::stoi(value());
      if (options.arm_joints < 1 || options.arm_joints > 64)
        throw std::invalid_argument("--arm takes 1 to 64 joints");
    } else if (arg == "--no-gnat") {
      options.gnat = false;
    } else {
      throw std::invalid_argument("unknown argument " + arg +
                                  " (see the usage line at the top of knn_bench.cpp)");
    }
  }
  return options;
}

// Piano milestones, shape [n, 7]: x y z qw qx qy qz.
std::vector<float> piano_milestones(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<float> q(n * 7);
  const double two_pi = 6.283185307179586;
  for (std::size_t i = 0; i < n; ++i) {
    float* p = q.data() + i * 7;
    p[0] = static_cast<float>(10 * unit(rng));
    p[1] = static_cast<float>(8 * unit(rng));
    p[2] = static_cast<float>(3 * unit(rng));
    // Shoemake: uniform on SO(3).
    const double u1 = unit(rng), u2 = unit(rng), u3 = unit(rng);
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    p[3] = static_cast<float>(b * std::cos(two_pi * u3));
    p[4] = static_cast<float>(a * std::sin(two_pi * u2));
    p[5] = static_cast<float>(a * std::cos(two_pi * u2));
    p[6] = static_cast<float>(b * std::sin(two_pi * u3));
  }
  return q;
}

// Arm milestones, shape [n, joints]: each joint uniform in [-2.9, 2.9].
std::vector<float> arm_milestones(std::size_t n, int joints, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> joint(-2.9, 2.9);
  std::vector<float> q(n * joints);
  for (float& x : q) x = static_cast<float>(joint(rng));
  return q;
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t m = values.size() / 2;
  return values.size() % 2 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

// Whether two neighbour lists of point i (each shape [k], nearest first, -1 padded) hold
// the same points up to ties: any point in one list but not the other lies at the larger
// list's k-th distance (within float tolerance), recomputed here with the metric.
bool same_up_to_ties(const ConfigurationMetric& metric, const std::vector<float>& points,
                     std::size_t i, const int* a, const int* b, int k) {
  const float* p = points.data() + i * metric.width();
  auto distance = [&](int j) {
    return gplanner::configuration_distance(metric, p, points.data() + j * metric.width());
  };
  float last = 0;
  for (int r = 0; r < k; ++r) {
    if (a[r] >= 0) last = std::max(last, distance(a[r]));
    if (b[r] >= 0) last = std::max(last, distance(b[r]));
  }
  const float tolerance = 1e-5f * last + 1e-5f;
  for (int pass = 0; pass < 2; ++pass) {
    const int* x = pass == 0 ? a : b;
    const int* y = pass == 0 ? b : a;
    for (int r = 0; r < k; ++r) {
      if (x[r] < 0 || std::find(y, y + k, x[r]) != y + k) continue;
      if (distance(x[r]) < last - tolerance) return false;
    }
  }
  return true;
}

double agreement(const ConfigurationMetric& metric, const std::vector<float>& points,
                 const std::vector<int>& a, const std::vector<int>& b, int k) {
  const std::size_t n = points.size() / metric.width();
  std::size_t same = 0;
  for (std::size_t i = 0; i < n; ++i)
    same += same_up_to_ties(metric, points, i, a.data() + i * k, b.data() + i * k, k);
  return n ? static_cast<double>(same) / n : 1.0;
}

// A milestone as OMPL's nearest-neighbour structures hold it.
struct Milestone {
  int index;
  const float* q;  // shape [width]
  bool operator==(const Milestone& other) const { return index == other.index; }
  bool operator!=(const Milestone& other) const { return index != other.index; }
};

int run(const Options& options) {
  ConfigurationMetric metric;
  const std::size_t n = options.points;
  const int k = options.k;
  std::vector<float> points;
  if (options.arm_joints > 0) {
    metric.joint_count = options.arm_joints;
    points = arm_milestones(n, options.arm_joints, options.seed);
  } else {
    metric.base = gplanner::MetricBase::kFloating;
    points = piano_milestones(n, options.seed);
  }
  const int width = metric.width();

  std::ostringstream json;
  json << "{\"benchmark\":\"knn\",\"robot\":\""
       << (options.arm_joints > 0 ? "arm-" + std::to_string(options.arm_joints) : "piano")
       << "\",\"points\":" << n << ",\"k\":" << k;

  // GPU: one warm-up call (device buffers, module load), then the timed runs.
  std::string reason;
  if (!gplanner::gpu_nearest_neighbors_available(&reason)) {
    std::cerr << "gplanner_knn_bench: no GPU: " << reason << "\n";
    return 1;
  }
  gplanner::GpuNearestNeighbors gpu;
  const auto first_call = std::chrono::steady_clock::now();
  NeighborTable on_gpu = gpu.all_nearest(metric, points.data(), n, k);
  const double first_call_ms = milliseconds_since(first_call);
  std::vector<double> gpu_ms, search_ms, wall_ms;
  for (int r = 0; r < options.runs; ++r) {
    const auto start = std::chrono::steady_clock::now();
    on_gpu = gpu.all_nearest(metric, points.data(), n, k);
    wall_ms.push_back(milliseconds_since(start));
    gpu_ms.push_back(gpu.last_stats().milliseconds);
    search_ms.push_back(gpu.last_stats().search_milliseconds);
  }
  const gplanner::GpuKnnStats stats = gpu.last_stats();
  const double gpu_median = median(gpu_ms);
  json << ",\"device\":\"" << gpu.device_name() << "\",\"gpu_runs\":" << options.runs
       << ",\"gpu_ms\":" << gpu_median << ",\"gpu_search_ms\":" << median(search_ms)
       << ",\"gpu_wall_ms\":" << median(wall_ms) << ",\"gpu_first_call_wall_ms\":" << first_call_ms
       << ",\"gpu_ms_min\":" << *std::min_element(gpu_ms.begin(), gpu_ms.end())
       << ",\"gpu_ms_max\":" << *std::max_element(gpu_ms.begin(), gpu_ms.end())
       << ",\"tiles\":" << stats.tiles << ",\"tiles_loaded\":" << stats.tiles_visited
       << ",\"candidate_pairs\":" << stats.candidate_pairs
       << ",\"distance_evaluations\":" << stats.distance_evaluations
       << ",\"candidate_fraction_of_n2\":"
       << static_cast<double>(stats.candidate_pairs) / (static_cast<double>(n) * n);

  if (options.cpu) {
    const int threads = gplanner::resolve_thread_count(0);
    const auto start = std::chrono::steady_clock::now();
    const NeighborTable on_cpu = gplanner::all_nearest_neighbors_cpu(metric, points.data(), n, k);
    const double cpu_ms = milliseconds_since(start);
    json << ",\"cpu_reference_ms\":" << cpu_ms << ",\"cpu_threads\":" << threads
         << ",\"cpu_over_gpu\":" << cpu_ms / gpu_median
         << ",\"gpu_matches_cpu\":" << agreement(metric, points, on_cpu.indices, on_gpu.indices, k);
  }

  if (options.gnat) {
    ompl::NearestNeighborsGNAT<Milestone> gnat;
    gnat.setDistanceFunction([&metric](const Milestone& a, const Milestone& b) {
      return static_cast<double>(gplanner::configuration_distance(metric, a.q, b.q));
    });
    std::vector<Milestone> milestones(n);
    for (std::size_t i = 0; i < n; ++i)
      milestones[i] = {static_cast<int>(i), points.data() + i * width};
    auto start = std::chrono::steady_clock::now();
    gnat.add(milestones);
    const double build_ms = milliseconds_since(start);
    std::vector<int> on_gnat(n * k, -1);
    std::vector<Milestone> found;
    start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < n; ++i) {
      // k + 1: the milestone itself is in the structure, as in OMPL's PRM.
      gnat.nearestK(milestones[i], k + 1, found);
      int r = 0;
      for (const Milestone& m : found) {
        if (m.index == static_cast<int>(i) || r == k) continue;
        on_gnat[i * k + r++] = m.index;
      }
    }
    const double query_ms = milliseconds_since(start);
    json << ",\"gnat_build_ms\":" << build_ms << ",\"gnat_query_ms\":" << query_ms
         << ",\"gnat_total_ms\":" << build_ms + query_ms
         << ",\"gnat_total_over_gpu\":" << (build_ms + query_ms) / gpu_median
         << ",\"gnat_query_over_gpu\":" << query_ms / gpu_median
         << ",\"gnat_matches_gpu\":" << agreement(metric, points, on_gnat, on_gpu.indices, k);
  }
  json << "}";
  std::cout << json.str() << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse(argc, argv));
  } catch (const std::exception& error) {
    std::cerr << "gplanner_knn_bench: " << error.what() << "\n";
    return 2;
  }
}
