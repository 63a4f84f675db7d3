#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/neighbor_finder.h moved to gplanner/planner/planning/neighbor_finder.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/neighbor_finder.h is deprecated (gplanner 0.2.0): include gplanner/planner/planning/neighbor_finder.h")
#include "gplanner/planner/planning/neighbor_finder.h"
