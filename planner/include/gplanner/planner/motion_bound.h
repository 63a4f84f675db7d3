#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/motion_bound.h moved to gplanner/planner/planning/motion_bound.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/motion_bound.h is deprecated (gplanner 0.2.0): include gplanner/planner/planning/motion_bound.h")
#include "gplanner/planner/planning/motion_bound.h"
