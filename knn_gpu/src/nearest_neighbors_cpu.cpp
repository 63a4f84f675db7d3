// The CPU reference: exact brute force over all pairs, rows shared among std::threads.
// Obviously right rather than fast: the GPU search is tested against it.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "gplanner/common/parallel_for.h"
#include "gplanner/knn_gpu/detail/metric_bounds.h"
#include "gplanner/knn_gpu/nearest_neighbors.h"
#include "knn_checks.h"

namespace gplanner {
namespace {

constexpr int kNoIndex = -1;

// The k best (distance, index) pairs seen so far, sorted by neighbor_before().
class BestK {
 public:
  explicit BestK(int k) : k_(k) {
    distances_.reserve(k);
    indices_.reserve(k);
  }
  void clear() {
    distances_.clear();
    indices_.clear();
  }
  void offer(float distance, int index) {
    const int size = static_cast<int>(distances_.size());
    if (size == k_ && !detail::neighbor_before(distance, index, distances_.back(), indices_.back()))
      return;
    int slot = size == k_ ? size - 1 : size;
    if (size < k_) {
      distances_.push_back(0);
      indices_.push_back(0);
    }
    while (slot > 0 &&
           detail::neighbor_before(distance, index, distances_[slot - 1], indices_[slot - 1])) {
      distances_[slot] = distances_[slot - 1];
      indices_[slot] = indices_[slot - 1];
      --slot;
    }
    distances_[slot] = distance;
    indices_[slot] = index;
  }
  // Writes the row, padded to k; distances and indices: shape [k].
  void write(float* distances, int* indices) const {
    const std::size_t size = distances_.size();
    std::copy(distances_.begin(), distances_.end(), distances);
    std::copy(indices_.begin(), indices_.end(), indices);
    std::fill(distances + size, distances + k_, kUnboundedRadius);
    std::fill(indices + size, indices + k_, kNoIndex);
  }

 private:
  int k_;
  std::vector<float> distances_;
  std::vector<int> indices_;
};

// Runs row(r, best) for every r in [0, rows), handing out blocks of rows to the threads.
template <typename RowFunction>
void for_each_row(std::size_t rows, int k, int threads, const RowFunction& row) {
  const std::size_t wanted = static_cast<std::size_t>(resolve_thread_count(threads));
  const std::size_t count = std::max<std::size_t>(1, std::min(wanted, rows));
  constexpr std::size_t kBlock = 16;
  std::atomic<std::size_t> next{0};
  auto work = [&]() {
    BestK best(k);
    while (true) {
      const std::size_t begin = next.fetch_add(kBlock);
      if (begin >= rows) return;
      const std::size_t end = std::min(rows, begin + kBlock);
      for (std::size_t r = begin; r < end; ++r) {
        best.clear();
        row(r, best);
      }
    }
  };
  std::vector<std::thread> pool;
  try {
    for (std::size_t t = 1; t < count; ++t) pool.emplace_back(work);
  } catch (const std::system_error&) {
    // A thread the system fails to start: those started and this one do all rows.
  }
  work();
  for (std::thread& thread : pool) thread.join();
}

NeighborTable empty_table(std::size_t rows, int k) {
  NeighborTable table;
  table.k = k;
  table.rows = rows;
  table.indices.resize(rows * k);
  table.distances.resize(rows * k);
  return table;
}

}  // namespace

int NeighborTable::count(std::size_t row) const {
  int c = 0;
  while (c < k && indices[row * k + c] != kNoIndex) ++c;
  return c;
}

NeighborTable all_nearest_neighbors_cpu(const ConfigurationMetric& metric, const float* points,
                                        std::size_t n, int k, float radius, int threads) {
  detail::check_knn_arguments(metric, n, k, radius);
  NeighborTable table = empty_table(n, k);
  const std::size_t width = metric.width();
  for_each_row(n, k, threads, [&](std::size_t i, BestK& best) {
    const float* p = points + i * width;
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i) continue;
      const float d = configuration_distance(metric, p, points + j * width);
      if (d <= radius) best.offer(d, static_cast<int>(j));
    }
    best.write(table.distances.data() + i * k, table.indices.data() + i * k);
  });
  return table;
}

NeighborTable nearest_neighbors_cpu(const ConfigurationMetric& metric, const float* points,
                                    std::size_t n, const float* queries, std::size_t m, int k,
                                    float radius, int threads) {
  detail::check_knn_arguments(metric, n, k, radius);
  NeighborTable table = empty_table(m, k);
  const std::size_t width = metric.width();
  for_each_row(m, k, threads, [&](std::size_t i, BestK& best) {
    const float* q = queries + i * width;
    for (std::size_t j = 0; j < n; ++j) {
      const float d = configuration_distance(metric, q, points + j * width);
      if (d <= radius) best.offer(d, static_cast<int>(j));
    }
    best.write(table.distances.data() + i * k, table.indices.data() + i * k);
  });
  return table;
}

}  // namespace gplanner
