#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/robot_model.h moved to gplanner/planner/scene/robot_model.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/robot_model.h is deprecated (gplanner 0.2.0): include gplanner/planner/scene/robot_model.h")
#include "gplanner/planner/scene/robot_model.h"
