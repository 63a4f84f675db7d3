#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/scene.h moved to gplanner/planner/scene/scene.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/scene.h is deprecated (gplanner 0.2.0): include gplanner/planner/scene/scene.h")
#include "gplanner/planner/scene/scene.h"
