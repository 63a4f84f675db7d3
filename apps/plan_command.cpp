#include "plan_command.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "command_line.h"
#include "gplanner/common/parallel_for.h"
#include "gplanner/common/physical_memory.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/output/output_paths.h"
#include "gplanner/planner/output/path_file.h"
#include "gplanner/planner/output/path_picture.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/roadmap.h"
#include "gplanner/planner/planning/roadmap_planner.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/input_file.h"
#include "gplanner/planner/scene/scene.h"
#include "interruption.h"
#include "json_line.h"
#include "plan_report.h"

namespace gplan {
namespace {

// "--out FILE" for messages.
std::string output_name(const gplanner::NamedFile& output) {
  return output.name + " " + output.path;
}

}  // namespace

int run_plan(int argc, char** argv) {
  catch_interruptions();
  const CommandLine args(
      argc, argv, 2,
      {"planner", "backend", "seed", "time-limit", "milestones", "traversal", "threads",
       "load-roadmap", "save-roadmap", "out", "picture", "edges", "path-check"},
      {"json"});
  if (args.positionals().size() != 1)
    throw UsageError("gplan plan takes one scene file, not " +
                     std::to_string(args.positionals().size()) + "; give exactly one");
  const std::string scene_file = args.positionals()[0];
  gplanner::RoadmapStrategy strategy = gplanner::RoadmapStrategy::kLazyPrm;
  if (!gplanner::parse_strategy(args.text("planner", "lazyprm"), &strategy))
    throw UsageError("--planner: '" + args.text("planner", "") + "' is not one of lazyprm, prm");
  const std::string backend = args.text("backend", "gpu");
  gplanner::CheckerOptions checker_options;
  checker_options.threads = static_cast<int>(args.count("threads", 0, 0, gplanner::kMaxThreads));
  if (args.has("traversal") &&
      !gplanner::parse_traversal(args.text("traversal", ""), &checker_options.gpu.traversal)) {
    throw UsageError("--traversal: '" + args.text("traversal", "") +
                     "' is not one of basic, packet, balanced");
  }
  if (args.has("traversal") && backend != "gpu")
    throw UsageError("--traversal applies to the gpu backend only; add --backend gpu");
  gplanner::EdgeChecks edges = gplanner::EdgeChecks::kSampled;
  if (!gplanner::parse_edge_checks(args.text("edges", "sampled"), &edges))
    throw UsageError("--edges: '" + args.text("edges", "") + "' is not one of sampled, certified");
  const std::string path_check = args.text("path-check", "certified");
  if (path_check != "certified" && path_check != "fine")
    throw UsageError("--path-check: '" + path_check + "' is not one of certified, fine");
  if (edges == gplanner::EdgeChecks::kCertified && path_check == "fine")
    throw UsageError(
        "--path-check fine with --edges certified: certified edges make a certified path; "
        "leave out --path-check");
  const std::string out = args.text("out", "");
  const std::string save = args.text("save-roadmap", "");
  const std::string load = args.text("load-roadmap", "");
  const std::string picture = args.text("picture", "");
  // Every output checked before any work (gplanner::check_output_paths): against the
  // inputs named here, then against every file the scene loads.
  std::vector<gplanner::NamedFile> outputs;
  for (const char* option : {"out", "picture", "save-roadmap"}) {
    if (args.has(option)) outputs.push_back({std::string("--") + option, args.text(option, "")});
  }
  std::vector<gplanner::NamedFile> inputs{{"the scene file", scene_file}};
  if (args.has("load-roadmap")) inputs.push_back({"the --load-roadmap file", load});
  gplanner::check_output_paths(outputs, inputs);
  if (args.has("load-roadmap"))
    gplanner::check_input_file(load, gplanner::kRoadmapFile, {"--load-roadmap", 0, ""});

  const auto setup_start = std::chrono::steady_clock::now();
  const gplanner::Scene scene = gplanner::load_scene(scene_file);
  for (const std::string& notice : scene.notices)
    std::cerr << "notice: " << gplanner::terminal_text(notice) << "\n";
  for (const std::string& file : scene.input_files)
    inputs.push_back({"a file the scene loads", file});
  gplanner::check_output_paths(outputs, inputs);
  std::vector<std::string> unwritten;
  for (const gplanner::NamedFile& output : outputs) unwritten.push_back(output_name(output));
  if (interrupted()) return report_interruption({}, unwritten);
  gplanner::PlanOptions options = gplanner::plan_options(scene);
  options.seed = args.count("seed", options.seed, 0, ~0ULL);
  options.time_limit_s = args.positive_number("time-limit", options.time_limit_s);
  options.milestones = args.count("milestones", options.milestones, 1, gplanner::kMaxMilestones);
  options.edges = edges;
  options.certify_path = path_check == "certified";
  // The first round's roadmap, before it is begun (later rounds stop at memory).
  const double roadmap_bytes =
      gplanner::roadmap_bytes(options.milestones, scene.space.width(), options.neighbors);
  if (!gplanner::fits_in_memory(roadmap_bytes)) {
    const std::string problem = "the roadmap of " + std::to_string(options.milestones) +
                                " milestones needs about " + gplanner::memory_text(roadmap_bytes) +
                                ", more than half of this machine's " +
                                gplanner::memory_text(gplanner::physical_memory_bytes()) +
                                " of memory; give fewer milestones";
    if (args.has("milestones")) throw UsageError("--milestones: " + problem);
    throw gplanner::InputError({scene_file, 0, "planner.roadmap.milestones"}, problem);
  }

  std::unique_ptr<gplanner::CollisionChecker> checker;
  try {
    std::string notice;
    checker = gplanner::make_collision_checker(scene, backend, checker_options, &notice);
    if (!notice.empty()) std::cerr << "notice: " << gplanner::terminal_text(notice) << "\n";
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--backend: ") + e.what());
  }
  gplanner::check_start_and_goal(scene, checker.get());
  const gplanner::ConfigurationMetric metric = gplanner::make_metric(scene.space, scene.planner);
  std::string knn_notice;
  std::unique_ptr<gplanner::NeighborFinder> neighbors =
      gplanner::make_neighbor_finder(metric, checker->backend(), &knn_notice);
  if (!knn_notice.empty()) std::cerr << "notice: " << gplanner::terminal_text(knn_notice) << "\n";
  options.should_stop = [] { return interrupted(); };

  // Progress: a line updated in place on a terminal, a line per round otherwise once
  // planning has taken a second.
  const bool terminal = isatty(STDERR_FILENO);
  options.progress = [&](const gplanner::PlanProgress& p) {
    if (!terminal && (p.elapsed_s < 1.0 || std::string(p.stage) != "neighbours")) return;
    std::ostringstream line;
    line << "round " << p.round << ": " << p.stage << ", " << p.milestones << " milestones, "
         << p.edges << " edges (" << p.edges_valid << " known valid), " << std::fixed
         << std::setprecision(1) << p.elapsed_s << " s";
    if (terminal) {
      std::cerr << "\r" << std::left << std::setw(90) << line.str() << std::flush;
    } else {
      std::cerr << line.str() << "\n";
    }
  };

  gplanner::RoadmapPlanner planner(scene, checker.get(), neighbors.get(), strategy, options);
  if (args.has("load-roadmap")) planner.set_roadmap(gplanner::load_roadmap(scene, load));
  // Setup (scene, checker, roadmap file) apart from planning, which --time-limit bounds.
  const double setup_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count();
  const gplanner::PlanResult result = planner.solve(scene.start.data(), scene.goal.data());
  if (terminal) std::cerr << "\r" << std::string(90, ' ') << "\r" << std::flush;

  // The outputs, each written whole or not at all; a signal stops before the next one.
  std::vector<std::string> written;
  const auto write = [&](const std::string& option, const std::function<void()>& write_file) {
    const auto output =
        std::find_if(outputs.begin(), outputs.end(),
                     [&](const gplanner::NamedFile& o) { return o.name == option; });
    if (output == outputs.end() || interrupted()) return;
    write_file();
    written.push_back(output_name(*output));
    unwritten.erase(std::find(unwritten.begin(), unwritten.end(), output_name(*output)));
  };
  write("--save-roadmap", [&] { gplanner::save_roadmap(planner.roadmap(), scene, save); });
  if (result.solved) {
    write("--out", [&] {
      gplanner::write_path_file(out, scene, result, gplanner::strategy_name(strategy),
                                checker->backend());
    });
    write("--picture", [&] { gplanner::write_path_picture(picture, scene, result.path); });
  }
  if (interrupted()) return report_interruption(written, unwritten);

  PlanReport report;
  report.scene_file = scene_file;
  report.scene_name = scene.name;
  report.dof = scene.space.dof();
  report.width = scene.space.width();
  report.planner = gplanner::strategy_name(strategy);
  report.backend = checker->backend();
  report.knn = neighbors->device();
  report.edges = gplanner::edge_checks_name(options.edges);
  report.certified_path =
      options.certify_path || options.edges == gplanner::EdgeChecks::kCertified;
  report.final_check_refinement = options.final_check_refinement;
  report.seed = options.seed;
  report.result = result;
  report.setup_s = setup_s;
  report.written = written;
  std::cout << report.text();
  if (args.flag("json")) std::cout << json_line(report.json());
  if (!result.solved && result.stop_reason == "memory limit") {
    std::cerr << "gplan: no path found in " << result.milestones << " milestones, and a "
              << "larger roadmap would need more than half of this machine's memory; try "
              << "another --seed or the scene's planner.sampler settings\n";
    return 4;
  }
  if (!result.solved) {
    std::cerr << "gplan: no path found within " << options.time_limit_s << " s ("
              << result.milestones << " milestones); raise "
              << (args.has("time-limit") ? "--time-limit"
                                         : "--time-limit (or the scene's planner.time_limit_s)")
              << " or the scene's planner.roadmap.milestones\n";
    if (!unwritten.empty()) {
      std::string files;
      for (const std::string& file : unwritten) files += (files.empty() ? "" : ", ") + file;
      std::cerr << "gplan: no path, so nothing written to " << gplanner::terminal_text(files)
                << "; what was there is left as it was\n";
    }
    return 4;
  }
  return 0;
}

}  // namespace gplan
