#include "check_report.h"

#include <iomanip>
#include <sstream>

#include "gplanner/planner/output/text_escaping.h"

namespace gplan {
namespace {

std::string gpu_text(const GpuCallReport& gpu) {
  const gplanner::GpuCheckStats& stats = gpu.stats;
  std::ostringstream out;
  out << gpu.device << ", " << gpu.traversal << " traversal, " << std::setprecision(3)
      << stats.milliseconds << " ms on the GPU in " << stats.chunks << " chunk(s), "
      << stats.bv_tests << " BV tests, " << stats.triangle_tests << " triangle tests";
  if (stats.jobs) out << ", " << stats.jobs << " body pairs past the broad phase";
  if (stats.rounds) out << ", " << stats.rounds << " rounds";
  if (stats.warp_per_pair) out << ", one kernel (small batch)";
  if (!stats.round_tasks.empty()) {
    out << "; tasks per round:";
    for (const unsigned tasks : stats.round_tasks) out << " " << tasks;
  }
  if (stats.finished_tasks) out << "; then " << stats.finished_tasks << " tasks a warp each";
  return out.str();
}

}  // namespace

bool CheckReport::band_broken() const {
  return compare &&
         compare->comparison.missed_collisions + compare->comparison.extra_outside_band > 0;
}

std::string CheckReport::text() const {
  using gplanner::terminal_text;
  std::ostringstream out;
  out << "scene       " << terminal_text(scene_file) << " (" << terminal_text(scene_name)
      << "), loaded in " << std::fixed << std::setprecision(3) << load_s << " s\n"
      << "robot       " << terminal_text(robot_name) << ": " << links << " link"
      << (links == 1 ? "" : "s") << ", " << robot_triangles << " triangles, " << checked_pairs
      << " checked link pairs; " << base << " base, " << dof << " DOF (" << width << " floats)\n"
      << "obstacles   " << obstacles << " (" << obstacle_triangles << " triangles; "
      << dropped_obstacle_triangles << " out of the robot's reach dropped)\n"
      << "tolerance   delta = " << std::scientific << std::setprecision(2) << delta << std::fixed
      << " m\n"
      << "backend     " << backend << "\n"
      << "start, goal free; straight line start -> goal ";
  if (straight_line_collision >= 0) {
    out << "collides (first at " << std::setprecision(1) << 100 * straight_line_collision
        << "% of the way)\n";
  } else {
    out << "is free\n";
  }
  out << "checked     " << n << " configurations (seed " << seed << ")\n"
      << "collisions  " << collisions << " (" << std::setprecision(2) << 100 * collision_fraction()
      << "%)\n"
      << "time        " << std::setprecision(4) << seconds << " s"
      << (repeat > 1 ? " (median of " + std::to_string(repeat) + " runs)" : "") << ", "
      << std::setprecision(0) << queries_per_second() << " queries/s\n";
  if (gpu) out << "gpu         " << gpu_text(*gpu) << "\n";
  if (compare) {
    const gplanner::CheckerComparison& c = compare->comparison;
    out << "compare     " << backend << " vs " << compare->backend << " (" << std::setprecision(4)
        << compare->seconds << " s, " << std::setprecision(1)
        << (seconds > 0 ? compare->seconds / seconds : 0.0) << "x the time): " << c.disagreements
        << " disagreements: " << c.missed_collisions << " missed collisions, "
        << c.extra_within_band << " extra within the band, " << c.extra_outside_band
        << " outside it";
    if (c.extra_within_band + c.extra_outside_band > 0) {
      out << " (largest FCL distance " << std::scientific << std::setprecision(2)
          << c.largest_extra_distance << std::fixed << " m)";
    }
    out << "\n";
    if (compare->gpu) out << "gpu         " << gpu_text(*compare->gpu) << "\n";
  }
  if (!written.empty()) out << "wrote       " << terminal_text(written) << "\n";
  return out.str();
}

nlohmann::ordered_json CheckReport::json() const {
  nlohmann::ordered_json j = {{"scene", scene_file},
                              {"name", scene_name},
                              {"backend", backend},
                              {"n", n},
                              {"seed", seed},
                              {"dof", dof},
                              {"width", width},
                              {"links", links},
                              {"robot_triangles", robot_triangles},
                              {"checked_pairs", checked_pairs},
                              {"obstacle_triangles", obstacle_triangles},
                              {"dropped_obstacle_triangles", dropped_obstacle_triangles},
                              {"delta", delta},
                              {"collisions", collisions},
                              {"collision_fraction", collision_fraction()},
                              {"seconds", seconds},
                              {"repeat", repeat},
                              {"queries_per_second", queries_per_second()},
                              {"straight_line_collides", straight_line_collision >= 0}};
  if (gpu) {
    j["traversal"] = gpu->traversal;
    j["gpu_ms"] = gpu->stats.milliseconds;
    j["bv_tests"] = gpu->stats.bv_tests;
    j["triangle_tests"] = gpu->stats.triangle_tests;
    j["rounds"] = gpu->stats.rounds;
    j["small_batch"] = gpu->stats.warp_per_pair;
  }
  if (compare) {
    const gplanner::CheckerComparison& c = compare->comparison;
    j["compare"] = {{"backend", compare->backend},
                    {"seconds", compare->seconds},
                    {"disagreements", c.disagreements},
                    {"missed_collisions", c.missed_collisions},
                    {"extra_within_band", c.extra_within_band},
                    {"extra_outside_band", c.extra_outside_band}};
  }
  return j;
}

}  // namespace gplan
