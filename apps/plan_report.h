#pragma once
// What `gplan plan` reports: the scene, the planner and checker that ran, the roadmap,
// the path and the time per stage; printed as text, and as one JSON line (--json).

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include "gplanner/planner/planning/plan_result.h"

namespace gplan {

struct PlanReport {
  std::string scene_file, scene_name;
  int dof = 0;
  std::size_t width = 0;       // floats per configuration
  std::string planner;         // the one that answered: lazyprm, prm, rrtconnect
  std::string planner_asked;   // --planner: auto (the default) or one of those
  std::string planner_reason;  // why auto chose `planner` ("" where it was named)
  std::string backend;         // the checker that ran (gpu, cpu, fcl)
  std::string knn;             // where the k-NN ran
  std::string edges;           // sampled, certified
  bool certified_path = true;  // else re-checked at 1/final_check_refinement
  int final_check_refinement = 10;
  unsigned long long seed = 0;
  gplanner::PlanResult result;
  double setup_s = 0;                // scene, checker and roadmap file, before planning
  std::vector<std::string> written;  // "--out FILE" and the like, as written

  std::size_t waypoints() const { return width ? result.path.size() / width : 0; }
  // The lines gplan plan prints (each ends in a newline).
  std::string text() const;
  // The --json line's object.
  nlohmann::ordered_json json() const;
};

}  // namespace gplan
