#include "gplanner/planner/planning/neighbor_finder.h"

#include <ompl/datastructures/NearestNeighborsGNAT.h>

#include <algorithm>
#include <array>
#include <random>

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

// Exact brute force over all hardware threads (knn_gpu's CPU search): each new point
// against all n. In many dimensions it beats GNAT, whose pruning fails there.
class BruteForceNeighborFinder : public NeighborFinder {
 public:
  explicit BruteForceNeighborFinder(const ConfigurationMetric& metric) : metric_(metric) {}
  std::string device() const override { return "cpu"; }
  bool nearest_of(const float* points, std::size_t n, std::size_t first, std::size_t end, int k,
                  std::vector<int>* indices) override {
    const std::size_t m = end - first;
    indices->assign(m * k, -1);
    if (m == 0) return true;
    // k + 1: each point finds itself among the n.
    const NeighborTable table =
        nearest_neighbors_cpu(metric_, points, n, points + first * metric_.width(), m, k + 1);
    for (std::size_t q = 0; q < m; ++q) {
      write_others(&table.indices[q * (k + 1)], k + 1, first + q, k, &(*indices)[q * k]);
    }
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
// 7-joint milestones on an H200: 0.3 ms warm, 2.8 ms cold; benchmarks/RESULTS.md).
class GpuNeighborFinder : public NeighborFinder {
 public:
  explicit GpuNeighborFinder(const ConfigurationMetric& metric) : metric_(metric) {
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
    gpu_.all_nearest(metric_, points.data(), kWarmPoints, kWarmNeighbors);
  }
  std::string device() const override { return "gpu"; }
  bool nearest_of(const float* points, std::size_t n, std::size_t first, std::size_t end, int k,
                  std::vector<int>* indices) override {
    ++device_calls_;
    const NeighborTable table = gpu_.all_nearest(metric_, points, n, k);
    indices->assign(table.indices.begin() + first * k, table.indices.begin() + end * k);
    return true;
  }
  bool searches_all_points() const override { return true; }
  std::size_t device_calls() const override { return device_calls_; }

 private:
  ConfigurationMetric metric_;
  GpuNearestNeighbors gpu_;
  std::size_t device_calls_ = 0;
};

}  // namespace

std::unique_ptr<NeighborFinder> make_neighbor_finder(const ConfigurationMetric& metric,
                                                     const std::string& backend,
                                                     std::string* notice) {
  if (backend == "gpu") {
    std::string reason;
    if (gpu_nearest_neighbors_available(&reason))
      return std::make_unique<GpuNeighborFinder>(metric);
    if (notice) *notice = "k-NN runs on the CPU: " + reason;
  }
  if (degrees_of_freedom(metric) > kBruteForceAboveDof)
    return std::make_unique<BruteForceNeighborFinder>(metric);
  return std::make_unique<GnatNeighborFinder>(metric);
}

}  // namespace gplanner
