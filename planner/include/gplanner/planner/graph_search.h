#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/graph_search.h moved to gplanner/planner/planning/graph_search.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/graph_search.h is deprecated (gplanner 0.2.0): include gplanner/planner/planning/graph_search.h")
#include "gplanner/planner/planning/graph_search.h"
