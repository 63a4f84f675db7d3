#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/roadmap.h moved to gplanner/planner/planning/roadmap.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/roadmap.h is deprecated (gplanner 0.2.0): include gplanner/planner/planning/roadmap.h")
#include "gplanner/planner/planning/roadmap.h"
