#include "gplanner/planner/planning/scene_metric.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gplanner {
namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

ConfigurationMetric make_metric(const ConfigurationSpace& space, const PlannerSettings& settings) {
  ConfigurationMetric metric;
  metric.base = space.base == BaseType::kFloating ? MetricBase::kFloating
                : space.base == BaseType::kPlanar ? MetricBase::kPlanar
                                                  : MetricBase::kNone;
  metric.joint_count = static_cast<int>(space.planned_joints.size());
  metric.position_weight = static_cast<float>(settings.distance_weights.position);
  metric.rotation_weight = static_cast<float>(settings.distance_weights.rotation);
  metric.joint_weight = static_cast<float>(settings.distance_weights.joint);
  for (int j = 0; j < metric.joint_count; ++j) {
    if (!space.continuous[j]) continue;
    if (j >= kMaxContinuousJointIndex) {
      throw std::invalid_argument("planned joint " + std::to_string(j) +
                                  " is continuous, but the metric marks continuous joints only "
                                  "among the first " +
                                  std::to_string(kMaxContinuousJointIndex));
    }
    metric.continuous_mask |= std::uint64_t(1) << j;
  }
  return metric;
}

double space_extent(const ConfigurationSpace& space, const ConfigurationMetric& metric) {
  double extent = 0;
  if (space.base == BaseType::kFloating) {
    extent += metric.position_weight * (space.base_max - space.base_min).norm() +
              metric.rotation_weight * kPi;
  } else if (space.base == BaseType::kPlanar) {
    extent += metric.position_weight * (space.base_max - space.base_min).head<2>().norm() +
              metric.rotation_weight * kPi;
  }
  double joints = 0;
  for (std::size_t j = 0; j < space.planned_joints.size(); ++j)
    joints += space.continuous[j] ? kPi : space.upper[j] - space.lower[j];
  return extent + metric.joint_weight * joints;
}

double distance(const ConfigurationMetric& metric, const float* a, const float* b) {
  return configuration_distance(metric, a, b);
}

}  // namespace gplanner
