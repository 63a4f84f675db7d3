#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/input_error.h moved to gplanner/planner/scene/input_error.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/input_error.h is deprecated (gplanner 0.2.0): include gplanner/planner/scene/input_error.h")
#include "gplanner/planner/scene/input_error.h"
