#include "plan_report.h"

#include <iomanip>
#include <sstream>

#include "gplanner/planner/output/text_escaping.h"

namespace gplan {

std::string PlanReport::text() const {
  using gplanner::terminal_text;
  const gplanner::PlanTimes& t = result.times;
  std::ostringstream out;
  out << std::fixed << "scene       " << terminal_text(scene_file) << " ("
      << terminal_text(scene_name) << "), " << dof << " DOF\n"
      << "planner     " << planner
      << (planner_reason.empty() ? "" : " (" + planner_asked + ": " + planner_reason + ")")
      << ", seed " << seed << ", " << backend << " backend, k-NN on the " << knn << "\n"
      << "edges       " << edges << ", path "
      << (certified_path ? "certified free along every motion"
                         : "re-checked at 1/" + std::to_string(final_check_refinement) +
                               " of the edge resolution")
      << "\n";
  if (planner == "rrtconnect") {
    out << "trees       " << result.milestones << " nodes from the start and the goal, "
        << result.rounds << " round(s) of extensions, " << result.samples_checked
        << " motion samples checked\n";
  } else {
    out << "roadmap     " << result.milestones << " milestones, " << result.edges << " edges ("
        << result.edges_checked << " checked, " << result.samples_checked << " edge samples), "
        << result.states_checked << " states checked, " << result.rounds << " round(s)\n";
  }
  if (result.solved) {
    out << "path        " << waypoints() << " waypoints, length " << std::setprecision(3)
        << result.length << " (" << result.length_before_shortcut << " before shortcutting)\n";
  } else {
    out << "path        none found (" << result.stop_reason << ")\n";
  }
  out << std::setprecision(4) << "time        " << t.total << " s: sampling " << t.sampling
      << ", state checks " << t.state_checks << ", k-NN " << t.knn << ", search " << t.search
      << ", edge checks " << t.edge_checks << ", shortcutting " << t.shortcutting << "\n";
  const gplanner::PlanGpuCalls& c = result.gpu_calls;
  if (c.total > 0) {
    out << "gpu calls   " << c.total << ": state checks " << c.state_checks << ", k-NN " << c.knn
        << ", search " << c.search << ", edge checks " << c.edge_checks << ", shortcutting "
        << c.shortcutting << "\n";
  }
  for (const std::string& file : written) out << "wrote       " << terminal_text(file) << "\n";
  return out.str();
}

nlohmann::ordered_json PlanReport::json() const {
  const gplanner::PlanTimes& t = result.times;
  // "edges" is the roadmap's edge count; how edges were checked is "edge_checks" (before
  // 0.2.0 both were "edges", the count last).
  return {{"scene", scene_file},
          {"name", scene_name},
          {"planner", planner},
          {"planner_asked", planner_asked},
          {"planner_reason", planner_reason},
          {"backend", backend},
          {"knn", knn},
          {"edge_checks", edges},
          {"path_check", certified_path ? "certified" : "fine"},
          {"seed", seed},
          {"solved", result.solved},
          {"stop_reason", result.stop_reason},
          {"length", result.length},
          {"length_before_shortcut", result.length_before_shortcut},
          {"waypoints", waypoints()},
          {"milestones", result.milestones},
          {"edges", result.edges},
          {"edges_checked", result.edges_checked},
          {"states_checked", result.states_checked},
          {"samples_checked", result.samples_checked},
          {"searches", result.searches},
          {"edge_batches", result.edge_batches},
          {"rounds", result.rounds},
          {"seconds", t.total},
          {"setup_seconds", setup_s},
          {"times",
           {{"sampling", t.sampling},
            {"state_checks", t.state_checks},
            {"knn", t.knn},
            {"search", t.search},
            {"edge_checks", t.edge_checks},
            {"shortcutting", t.shortcutting}}},
          {"gpu_calls",
           {{"state_checks", result.gpu_calls.state_checks},
            {"knn", result.gpu_calls.knn},
            {"search", result.gpu_calls.search},
            {"edge_checks", result.gpu_calls.edge_checks},
            {"shortcutting", result.gpu_calls.shortcutting},
            {"total", result.gpu_calls.total}}}};
}

}  // namespace gplan
