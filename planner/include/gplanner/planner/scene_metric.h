#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/scene_metric.h moved to gplanner/planner/planning/scene_metric.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/scene_metric.h is deprecated (gplanner 0.2.0): include gplanner/planner/planning/scene_metric.h")
#include "gplanner/planner/planning/scene_metric.h"
