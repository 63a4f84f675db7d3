#include "gplanner/planner/planning/nearest_node_index.h"

#include <cmath>

namespace gplanner {

NearestNodeIndex::NearestNodeIndex(const ConfigurationMetric& metric)
    : metric_(metric), width_(metric.width()) {
  by_columns_ = metric.base == MetricBase::kNone && metric.joint_count > 0;
  for (int j = 0; j < metric.joint_count; ++j) by_columns_ = by_columns_ && !metric.continuous(j);
  if (by_columns_) columns_.resize(metric.joint_count);
}

void NearestNodeIndex::clear() {
  size_ = 0;
  for (std::vector<float>& column : columns_) column.clear();
}

void NearestNodeIndex::add(const float* q) {
  for (std::size_t j = 0; j < columns_.size(); ++j) columns_[j].push_back(q[j]);
  ++size_;
}

// Built for AVX2 beside the baseline, the one the processor has chosen at load: twice
// the lanes per instruction, the same floats (no fused multiply-add, no reordering).
__attribute__((target_clones("avx2", "default"))) void NearestNodeIndex::column_distances(
    const float* q, std::size_t begin, std::size_t end, float* out) const {
  const std::size_t n = end - begin;
  // configuration_distance's joint sum, joint by joint: the same additions in the same
  // order for every node.
  for (std::size_t i = 0; i < n; ++i) out[i] = 0;
  for (std::size_t j = 0; j < columns_.size(); ++j) {
    const float* x = columns_[j].data() + begin;
    const float y = q[j];
    for (std::size_t i = 0; i < n; ++i) out[i] += std::fabs(x[i] - y);
  }
  const float base_term = 0, weight = metric_.joint_weight;
  for (std::size_t i = 0; i < n; ++i) out[i] = base_term + weight * out[i];
}

}  // namespace gplanner
