#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/path_file.h moved to gplanner/planner/output/path_file.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/path_file.h is deprecated (gplanner 0.2.0): include gplanner/planner/output/path_file.h")
#include "gplanner/planner/output/path_file.h"
