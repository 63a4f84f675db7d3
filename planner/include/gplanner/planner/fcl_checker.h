#pragma once
// Deprecated since 0.2.0, to be removed in 0.6: gplanner/planner/fcl_checker.h moved to gplanner/planner/checkers/fcl_checker.h
// (planner/ is split by stage); include that instead.
#pragma message("gplanner/planner/fcl_checker.h is deprecated (gplanner 0.2.0): include gplanner/planner/checkers/fcl_checker.h")
#include "gplanner/planner/checkers/fcl_checker.h"
