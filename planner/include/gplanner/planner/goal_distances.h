#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/goal_distances.h moved to gplanner/planner/planning/goal_distances.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/goal_distances.h is deprecated (gplanner 0.2.0): include gplanner/planner/planning/goal_distances.h")
#include "gplanner/planner/planning/goal_distances.h"
