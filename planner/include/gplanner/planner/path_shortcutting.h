#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/path_shortcutting.h moved to gplanner/planner/planning/path_shortcutting.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/path_shortcutting.h is deprecated (gplanner 0.2.0): include gplanner/planner/planning/path_shortcutting.h")
#include "gplanner/planner/planning/path_shortcutting.h"
