#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/local_planner.h moved to gplanner/planner/planning/local_planner.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/local_planner.h is deprecated (gplanner 0.2.0): include gplanner/planner/planning/local_planner.h")
#include "gplanner/planner/planning/local_planner.h"
