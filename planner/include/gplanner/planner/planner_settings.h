#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/planner_settings.h moved to gplanner/planner/scene/planner_settings.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/planner_settings.h is deprecated (gplanner 0.2.0): include gplanner/planner/scene/planner_settings.h")
#include "gplanner/planner/scene/planner_settings.h"
