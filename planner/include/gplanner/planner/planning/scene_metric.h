#pragma once
// The planner's metric for a scene (knn_gpu's ConfigurationMetric, with the weights of
// the scene's planner settings) and the largest extent of its configuration space under
// that metric, from which edge resolutions are taken (as OMPL takes them from
// StateSpace::getMaximumExtent).

#include "gplanner/knn_gpu/configuration_metric.h"
#include "gplanner/planner/scene/configuration_space.h"
#include "gplanner/planner/scene/planner_settings.h"

namespace gplanner {

// Throws std::invalid_argument when a continuous joint lies beyond the metric's mask.
ConfigurationMetric make_metric(const ConfigurationSpace& space, const PlannerSettings& settings);

// The largest distance two configurations of the space can have under the metric: the
// base bounds' diagonal, a half turn for the rotation, every joint's range (a half turn
// for continuous joints), each weighted.
double space_extent(const ConfigurationSpace& space, const ConfigurationMetric& metric);

// configuration_distance in double for host callers, on float rows.
double distance(const ConfigurationMetric& metric, const float* a, const float* b);

}  // namespace gplanner
