#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/mesh_loader.h moved to gplanner/planner/scene/mesh_loader.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/mesh_loader.h is deprecated (gplanner 0.2.0): include gplanner/planner/scene/mesh_loader.h")
#include "gplanner/planner/scene/mesh_loader.h"
