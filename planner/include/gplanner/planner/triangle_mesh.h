#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/triangle_mesh.h moved to gplanner/planner/scene/triangle_mesh.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/triangle_mesh.h is deprecated (gplanner 0.2.0): include gplanner/planner/scene/triangle_mesh.h")
#include "gplanner/planner/scene/triangle_mesh.h"
