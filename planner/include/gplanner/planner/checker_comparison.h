#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/checker_comparison.h moved to gplanner/planner/checkers/checker_comparison.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/checker_comparison.h is deprecated (gplanner 0.2.0): include gplanner/planner/checkers/checker_comparison.h")
#include "gplanner/planner/checkers/checker_comparison.h"
