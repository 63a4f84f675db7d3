#include "gplanner/planner/planning/neighbor_finder.h"

#include <ompl/datastructures/NearestNeighborsGNAT.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "gplanner/common/parallel_for.h"
#include "gplanner/knn_gpu/nearest_neighbors.h"

namespace gplanner {
namespace {

// Writes to `row` (k wide, -1 filled) the first k of `count` candidates (nearest first;
// a negative index ends them) other than the point `self`, which a search among all the
// points finds too.
template <class Index>
void write_others(const Index* candidates, std::size_t count, std::size_t self, int k, int* row) {
  int rank = 0;
  for (std::size_t j = 0; j < count && rank < k; ++j) {
    const long long c = static_cast<long long>(candidates[j]);
    if (c < 0) break;
    if (static_cast<std::size_t>(c) != self) row[rank++] = static_cast<int>(c);
  }
}

// OMPL's GNAT over point indices, the points read from the caller's array at each call.
class GnatNeighborFinder : public NeighborFinder {
 public:
  explicit GnatNeighborFinder(const ConfigurationMetric& metric) : metric_(metric) { clear_tree(); }
  std::string device() const override { return "cpu"; }

  bool nearest_of(const float* points, std::size_t n, std::size_t first, std::size_t end, int k,
                  std::vector<int>* indices) override {
    points_ = points;
    // A fresh start (first 0) unless the last call was one, stopped while inserting.
    if ((first == 0 && !resuming_fresh_) || n < added_) clear_tree();
    resuming_fresh_ = false;
    indices->clear();
    // Insertion is most of the first call's time (seconds for millions of points):
    // the stop is polled every kStopPoll points.
    constexpr std::size_t kStopPoll = 1024;
    for (std::size_t i = added_, inserted = 0; i < n; ++i, ++inserted) {
      if (inserted % kStopPoll == kStopPoll - 1 && should_stop()) {
        resuming_fresh_ = first == 0;
        return false;
      }
      tree_->add(static_cast<std::uint32_t>(i));
      added_ = i + 1;
    }
    indices->assign((end - first) * k, -1);
    std::vector<std::uint32_t> found;
    for (std::size_t i = first; i < end; ++i) {
      tree_->nearestK(static_cast<std::uint32_t>(i), k + 1, found);
      write_others(found.data(), found.size(), i, k, &(*indices)[(i - first) * k]);
    }
    return true;
  }

  void reset() override {
    clear_tree();
    resuming_fresh_ = false;
  }

 private:
  void clear_tree() {
    tree_ = std::make_unique<ompl::NearestNeighborsGNAT<std::uint32_t>>();
    tree_->setDistanceFunction([this](const std::uint32_t& a, const std::uint32_t& b) {
      const int w = metric_.width();
      return static_cast<double>(configuration_distance(metric_, points_ + std::size_t(a) * w,
                                                        points_ + std::size_t(b) * w));
    });
    added_ = 0;
  }

  ConfigurationMetric metric_;
  const float* points_ = nullptr;
  std::size_t added_ = 0;
  bool resuming_fresh_ = false;  // the last call started afresh and stopped part way
  std::unique_ptr<ompl::NearestNeighborsGNAT<std::uint32_t>> tree_;
};

// Exact brute force on the pool's threads: each new point against all n. In many
// dimensions it beats GNAT, whose pruning fails there. The points' joint values are
// laid out joint by joint (one column per joint), so that a query's distances to a block
// of points are summed a joint at a time over the whole block, a loop the compiler
// vectorises; the base's terms, where the robot has a base, per pair as
// configuration_distance computes them. Each pair's sum is taken in
// configuration_distance's order (base term + weight x (joint 0 + joint 1 + ...)), so the
// distances are its own, bit for bit. Against knn_gpu's CPU reference (written to be
// obviously right, a thread started per call), the k-NN stage of a Panda plan on 2 cores
// took 5.5 ms instead of 22 ms for the 2,002 first milestones, 1.8 s instead of 10.3 s
// over rounds to 64,002 (MotionBenchMaker's cage).
class BruteForceNeighborFinder : public NeighborFinder {
 public:
  explicit BruteForceNeighborFinder(const ConfigurationMetric& metric) : metric_(metric) {}
  std::string device() const override { return "cpu"; }
  bool nearest_of(const float* points, std::size_t n, std::size_t first, std::size_t end, int k,
                  std::vector<int>* indices) override {
    const std::size_t m = end - first;
    indices->assign(m * k, -1);
    if (m == 0) return true;
    const std::size_t width = metric_.width();
    const int offset = metric_.base_width();
    const int joints = metric_.joint_count;
    // columns[j * n + i]: joint j of point i.
    std::vector<float> columns(static_cast<std::size_t>(joints) * n);
    for (std::size_t i = 0; i < n; ++i)
      for (int j = 0; j < joints; ++j) columns[j * n + i] = points[i * width + offset + j];
    ConfigurationMetric base_only = metric_;
    base_only.joint_count = 0;
    const int keep = k + 1;  // each point finds itself among the n
    constexpr std::size_t kBlock = 2048;  // points a query takes at a time
    parallel_for(
        m, resolve_thread_count(0),
        [&](std::size_t begin, std::size_t stop, int) {
          std::vector<float> best_d(keep), sum(kBlock), base(kBlock, 0.0f);
          std::vector<int> best_i(keep);
          for (std::size_t q = begin; q < stop; ++q) {
            const float* p = points + (first + q) * width;
            int size = 0;
            float worst = std::numeric_limits<float>::infinity();  // while not full
            for (std::size_t b0 = 0; b0 < n; b0 += kBlock) {
              const std::size_t count = std::min(kBlock, n - b0);
              std::fill_n(sum.begin(), count, 0.0f);
              for (int j = 0; j < joints; ++j) {
                const float x = p[offset + j];
                const float* column = &columns[j * n + b0];
                if (metric_.continuous(j)) {
                  for (std::size_t i = 0; i < count; ++i) sum[i] += angle_difference(x, column[i]);
                } else {
                  for (std::size_t i = 0; i < count; ++i) sum[i] += std::fabs(x - column[i]);
                }
              }
              if (offset > 0) {
                for (std::size_t i = 0; i < count; ++i)
                  base[i] = configuration_distance(base_only, p, points + (b0 + i) * width);
              }
              for (std::size_t i = 0; i < count; ++i) {
                const float d = base[i] + metric_.joint_weight * sum[i];
                // Full: only a nearer one enters (ties: the lower index stays); not yet:
                // any distance but NaN (a point that is no configuration).
                if (size == keep ? !(d < worst) : !(d <= worst)) continue;
                int slot = size < keep ? size++ : keep - 1;
                while (slot > 0 && d < best_d[slot - 1]) {
                  best_d[slot] = best_d[slot - 1];
                  best_i[slot] = best_i[slot - 1];
                  --slot;
                }
                best_d[slot] = d;
                best_i[slot] = static_cast<int>(b0 + i);
                if (size == keep) worst = best_d[keep - 1];
              }
            }
            write_others(best_i.data(), size, first + q, k, &(*indices)[q * k]);
          }
        },
        16);
    return true;
  }
  double query_cost(std::size_t n) const override { return static_cast<double>(n); }

 private:
  ConfigurationMetric metric_;
};

// Degrees of freedom beyond which the CPU k-NN is brute force rather than GNAT, where
// GNAT's pruning fails (measured: benchmarks/history/tuning_notes.md, "CPU k-NN").
constexpr int kBruteForceAboveDof = 6;

int degrees_of_freedom(const ConfigurationMetric& metric) {
  const int base = metric.base == MetricBase::kFloating ? 6
                   : metric.base == MetricBase::kPlanar ? 3
                                                        : 0;
  return base + metric.joint_count;
}

// knn_gpu's all-points search, every call over all points. Warmed up when made (device
// buffers for a first round of a few thousand milestones, the kernels loaded): a
// plan's first k-NN call then costs its work, not the 2.5 ms of a first call (2,002
// 7-joint milestones on an H200: 0.3 ms warm, 2.8 ms cold; measured:
// benchmarks/history/issue33_fewer_gpu_calls_500f1e5.md).
class GpuNeighborFinder : public NeighborFinder {
 public:
  GpuNeighborFinder(const ConfigurationMetric& metric, int device)
      : metric_(metric), device_(device), gpu_(device) {
    constexpr std::size_t kWarmPoints = 4096;
    constexpr int kWarmNeighbors = 16;
    const int width = metric.width();
    std::vector<float> points(kWarmPoints * width);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> coordinate(-1, 1);
    for (float& x : points) x = coordinate(rng);
    if (metric.base == MetricBase::kFloating) {  // unit quaternions w x y z: the identity
      for (std::size_t i = 0; i < kWarmPoints; ++i)
        std::copy_n(std::array<float, 4>{1, 0, 0, 0}.data(), 4, &points[i * width + 3]);
    }
    std::vector<int> rows(kWarmPoints * kWarmNeighbors);
    gpu_.nearest_rows(metric_, points.data(), kWarmPoints, kWarmNeighbors, 0, kWarmPoints,
                      rows.data());
  }
  std::string device() const override { return "gpu"; }
  bool nearest_of(const float* points, std::size_t n, std::size_t first, std::size_t end, int k,
                  std::vector<int>* indices) override {
    ++device_calls_;
    indices->resize((end - first) * k);
    gpu_.nearest_rows(metric_, points, n, k, first, end, indices->data());
    return true;
  }
  bool searches_all_points() const override { return true; }
  std::size_t device_calls() const override {
    return device_calls_ + (way_costs_ ? way_costs_->calls() : 0);
  }
  // Made at the first use, on the finder's device; none where that fails (the host
  // computes the costs then).
  GpuWayCosts* way_costs() override {
    if (!way_costs_ && !way_costs_failed_) {
      try {
        way_costs_ = std::make_unique<GpuWayCosts>(device_);
      } catch (const std::exception&) {
        way_costs_failed_ = true;
      }
    }
    return way_costs_.get();
  }

 private:
  ConfigurationMetric metric_;
  int device_;
  GpuNearestNeighbors gpu_;
  std::unique_ptr<GpuWayCosts> way_costs_;
  bool way_costs_failed_ = false;
  std::size_t device_calls_ = 0;
};

}  // namespace

std::unique_ptr<NeighborFinder> make_neighbor_finder(const ConfigurationMetric& metric,
                                                     const std::string& backend,
                                                     std::string* notice, int device) {
  if (backend == "gpu") {
    std::string reason;
    if (gpu_nearest_neighbors_available(&reason))
      return std::make_unique<GpuNeighborFinder>(metric, std::max(device, 0));
    if (notice) *notice = "k-NN runs on the CPU: " + reason;
  }
  if (degrees_of_freedom(metric) > kBruteForceAboveDof)
    return std::make_unique<BruteForceNeighborFinder>(metric);
  return std::make_unique<GnatNeighborFinder>(metric);
}

}  // namespace gplanner
