#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/milestone_sampler.h moved to gplanner/planner/planning/milestone_sampler.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/milestone_sampler.h is deprecated (gplanner 0.2.0): include gplanner/planner/planning/milestone_sampler.h")
#include "gplanner/planner/planning/milestone_sampler.h"
