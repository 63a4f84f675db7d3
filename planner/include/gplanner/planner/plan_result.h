#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/plan_result.h moved to gplanner/planner/planning/plan_result.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/plan_result.h is deprecated (gplanner 0.2.0): include gplanner/planner/planning/plan_result.h")
#include "gplanner/planner/planning/plan_result.h"
