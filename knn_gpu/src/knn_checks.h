#pragma once
// Argument checks shared by the CPU reference and the GPU search: each error says what
// to change.

#include <climits>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "gplanner/knn_gpu/configuration_metric.h"

namespace gplanner {
namespace detail {

inline void check_knn_arguments(const ConfigurationMetric& metric, std::size_t n, int k,
                                float radius) {
  if (k < 1) throw std::invalid_argument("k-NN: k is " + std::to_string(k) + ", must be >= 1");
  if (std::isnan(radius) || radius < 0) {
    throw std::invalid_argument("k-NN: radius is " + std::to_string(radius) +
                                ", must be >= 0 (kUnboundedRadius for none)");
  }
  if (metric.base != MetricBase::kNone && metric.base != MetricBase::kPlanar &&
      metric.base != MetricBase::kFloating) {
    throw std::invalid_argument("k-NN: metric has an unknown base type");
  }
  if (metric.joint_count < 0) {
    throw std::invalid_argument("k-NN: metric joint_count is " +
                                std::to_string(metric.joint_count) + ", must be >= 0");
  }
  if (!(metric.position_weight >= 0) || !(metric.rotation_weight >= 0) ||
      !(metric.joint_weight >= 0) || std::isinf(metric.position_weight) ||
      std::isinf(metric.rotation_weight) || std::isinf(metric.joint_weight)) {
    throw std::invalid_argument("k-NN: metric weights must be finite and >= 0");
  }
  if (n > static_cast<std::size_t>(INT_MAX)) {
    throw std::invalid_argument("k-NN: " + std::to_string(n) +
                                " points exceed the int indices of NeighborTable");
  }
}

}  // namespace detail
}  // namespace gplanner
