#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/forward_kinematics.h moved to gplanner/planner/scene/forward_kinematics.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/forward_kinematics.h is deprecated (gplanner 0.2.0): include gplanner/planner/scene/forward_kinematics.h")
#include "gplanner/planner/scene/forward_kinematics.h"
