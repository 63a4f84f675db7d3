#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/configuration_space.h moved to gplanner/planner/scene/configuration_space.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/configuration_space.h is deprecated (gplanner 0.2.0): include gplanner/planner/scene/configuration_space.h")
#include "gplanner/planner/scene/configuration_space.h"
