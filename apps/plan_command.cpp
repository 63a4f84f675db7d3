#include "plan_command.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

#include "command_line.h"
#include "gplanner/common/parallel_for.h"
#include "gplanner/common/physical_memory.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/output/output_paths.h"
#include "gplanner/planner/output/path_file.h"
#include "gplanner/planner/output/path_picture.h"
#include "gplanner/planner/output/path_viewer.h"
#include "gplanner/planner/output/roadmap_file.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/planner_choice.h"
#include "gplanner/planner/planning/roadmap.h"
#include "gplanner/planner/planning/roadmap_planner.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/input_file.h"
#include "gplanner/planner/scene/scene.h"
#include "interruption.h"
#include "json_line.h"
#include "plan_report.h"
#include "view_command.h"

namespace gplan {
namespace {

// "--out FILE" for messages.
std::string output_name(const gplanner::NamedFile& output) {
  return output.name + " " + output.path;
}

// What `gplan plan` was asked, read from its arguments and checked before any work;
// seed, time limit and milestones where given (otherwise the scene's settings).
struct PlanRequest {
  std::string scene_file;
  gplanner::PlannerKind planner = gplanner::PlannerKind::kAuto;
  std::string backend;
  gplanner::CheckerOptions checker_options;
  gplanner::EdgeChecks edges = gplanner::EdgeChecks::kSampled;
  bool certify_path = true;  // --path-check certified (else fine)
  std::optional<unsigned long long> seed;
  std::optional<double> time_limit_s;
  std::optional<std::size_t> milestones;
  std::string out, save, picture, html;
  bool html_roadmap = false;                 // the roadmap drawn in --html
  std::optional<std::string> load;           // --load-roadmap FILE
  std::vector<gplanner::NamedFile> outputs;  // the output options given
  bool json = false;
};

PlanRequest read_plan_request(int argc, char** argv) {
  const CommandLine args(
      argc, argv, 2,
      {"planner", "backend", "seed", "time-limit", "milestones", "traversal", "threads", "device",
       "load-roadmap", "save-roadmap", "out", "picture", "html", "edges", "path-check"},
      {"json", "html-roadmap"});
  if (args.positionals().size() != 1)
    throw UsageError("gplan plan takes one scene file, not " +
                     std::to_string(args.positionals().size()) + "; give exactly one");
  PlanRequest r;
  r.scene_file = args.positionals()[0];
  if (!gplanner::parse_planner(args.text("planner", "auto"), &r.planner)) {
    throw UsageError("--planner: '" + args.text("planner", "") + "' is not one of " +
                     gplanner::planner_names());
  }
  if (!gplanner::keeps_roadmap(r.planner)) {
    for (const char* option : {"milestones", "load-roadmap", "save-roadmap"}) {
      if (args.has(option)) {
        throw UsageError(std::string("--") + option + " applies to the roadmap planners (" +
                         "lazyprm, prm), not to --planner " + gplanner::planner_name(r.planner));
      }
    }
  }
  r.backend = args.text("backend", "gpu");
  r.checker_options.threads = static_cast<int>(args.count("threads", 0, 0, gplanner::kMaxThreads));
  if (args.has("traversal") &&
      !gplanner::parse_traversal(args.text("traversal", ""), &r.checker_options.gpu.traversal)) {
    throw UsageError("--traversal: '" + args.text("traversal", "") +
                     "' is not one of basic, packet, balanced");
  }
  r.checker_options.gpu.device = args.gpu_device(0);
  for (const char* gpu_only : {"traversal", "device"}) {
    if (args.has(gpu_only) && r.backend != "gpu")
      throw UsageError(std::string("--") + gpu_only +
                       " applies to the gpu backend only; add --backend gpu");
  }
  if (!gplanner::parse_edge_checks(args.text("edges", "sampled"), &r.edges))
    throw UsageError("--edges: '" + args.text("edges", "") + "' is not one of sampled, certified");
  const std::string path_check = args.text("path-check", "certified");
  if (path_check != "certified" && path_check != "fine")
    throw UsageError("--path-check: '" + path_check + "' is not one of certified, fine");
  if (r.edges == gplanner::EdgeChecks::kCertified && path_check == "fine")
    throw UsageError(
        "--path-check fine with --edges certified: certified edges make a certified path; "
        "leave out --path-check");
  r.certify_path = path_check == "certified";
  r.out = args.text("out", "");
  r.save = args.text("save-roadmap", "");
  if (args.has("load-roadmap")) r.load = args.text("load-roadmap", "");
  r.picture = args.text("picture", "");
  r.html = args.text("html", "");
  r.html_roadmap = args.flag("html-roadmap");
  if (r.html_roadmap && !args.has("html"))
    throw UsageError("--html-roadmap draws in --html FILE; give it");
  if (r.html_roadmap && !gplanner::keeps_roadmap(r.planner))
    throw UsageError("--html-roadmap: --planner rrtconnect keeps no roadmap; use lazyprm or prm");
  if (args.has("html")) require_path_viewer();
  for (const char* option : {"out", "picture", "html", "save-roadmap"}) {
    if (args.has(option)) r.outputs.push_back({std::string("--") + option, args.text(option, "")});
  }
  if (args.has("seed")) r.seed = args.count("seed", 0, 0, ~0ULL);
  if (args.has("time-limit")) r.time_limit_s = args.positive_number("time-limit", 1);
  if (args.has("milestones"))
    r.milestones = args.count("milestones", 1, 1, gplanner::kMaxMilestones);
  r.json = args.flag("json");
  return r;
}

// The first round's roadmap, refused before it is begun where it would not fit (later
// rounds stop at memory).
void check_roadmap_fits(const PlanRequest& request, const gplanner::Scene& scene,
                        const gplanner::PlanOptions& options) {
  const double bytes =
      gplanner::roadmap_bytes(options.milestones, scene.space.width(), options.neighbors);
  if (gplanner::fits_in_memory(bytes)) return;
  const std::string problem = "the roadmap of " + std::to_string(options.milestones) +
                              " milestones needs about " + gplanner::memory_text(bytes) +
                              ", more than half of this machine's " +
                              gplanner::memory_text(gplanner::physical_memory_bytes()) +
                              " of memory; give fewer milestones";
  if (request.milestones) throw UsageError("--milestones: " + problem);
  throw gplanner::InputError({request.scene_file, 0, "planner.roadmap.milestones"}, problem);
}

// Progress: a line updated in place on a terminal, a line per round otherwise once
// planning has taken a second.
std::function<void(const gplanner::PlanProgress&)> progress_printer(bool terminal) {
  return [terminal](const gplanner::PlanProgress& p) {
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
}

// Exit 4: why no path was found, what to change, and which outputs were left as they were.
int report_no_path(const PlanRequest& request, const gplanner::PlanResult& result,
                   double time_limit_s, const std::vector<std::string>& unwritten) {
  if (result.stop_reason == "memory limit") {
    std::cerr << "gplan: no path found in " << result.milestones << " milestones, and a "
              << "larger roadmap would need more than half of this machine's memory; try "
              << "another --seed or the scene's planner.sampler settings\n";
    return 4;
  }
  std::cerr << "gplan: no path found within " << time_limit_s << " s (" << result.milestones
            << " milestones); raise "
            << (request.time_limit_s ? "--time-limit"
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

}  // namespace

int run_plan(int argc, char** argv) {
  catch_interruptions();
  const PlanRequest request = read_plan_request(argc, argv);
  // Every output checked before any work (gplanner::check_output_paths): against the
  // inputs named here, then against every file the scene loads.
  const std::vector<gplanner::NamedFile>& outputs = request.outputs;
  std::vector<gplanner::NamedFile> inputs{{"the scene file", request.scene_file}};
  if (request.load) inputs.push_back({"the --load-roadmap file", *request.load});
  gplanner::check_output_paths(outputs, inputs);
  if (request.load)
    gplanner::check_input_file(*request.load, gplanner::kRoadmapFile, {"--load-roadmap", 0, ""});

  const auto setup_start = std::chrono::steady_clock::now();
  const gplanner::Scene scene = gplanner::load_scene(request.scene_file);
  for (const std::string& notice : scene.notices)
    std::cerr << "notice: " << gplanner::terminal_text(notice) << "\n";
  for (const std::string& file : scene.input_files)
    inputs.push_back({"a file the scene loads", file});
  gplanner::check_output_paths(outputs, inputs);
  std::vector<std::string> unwritten;
  for (const gplanner::NamedFile& output : outputs) unwritten.push_back(output_name(output));
  if (interrupted()) return report_interruption({}, unwritten);
  gplanner::PlanOptions options = gplanner::plan_options(scene);
  if (request.seed) options.seed = *request.seed;
  if (request.time_limit_s) options.time_limit_s = *request.time_limit_s;
  if (request.milestones) options.milestones = *request.milestones;
  options.edges = request.edges;
  options.certify_path = request.certify_path;
  if (gplanner::keeps_roadmap(request.planner)) check_roadmap_fits(request, scene, options);

  std::unique_ptr<gplanner::CollisionChecker> checker;
  try {
    std::string notice;
    checker =
        gplanner::make_collision_checker(scene, request.backend, request.checker_options, &notice);
    if (!notice.empty()) std::cerr << "notice: " << gplanner::terminal_text(notice) << "\n";
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--backend: ") + e.what());
  }
  gplanner::check_start_and_goal(scene, checker.get());
  const gplanner::ConfigurationMetric metric = gplanner::make_metric(scene.space, scene.planner);
  // The roadmap planners' k-NN (the trees' nearest nodes are found on the host).
  std::unique_ptr<gplanner::NeighborFinder> neighbors;
  if (gplanner::keeps_roadmap(request.planner)) {  // auto may hand over to lazy PRM
    std::string knn_notice;
    neighbors = gplanner::make_neighbor_finder(metric, checker->backend(), &knn_notice,
                                               checker->gpu_device());
    if (!knn_notice.empty()) std::cerr << "notice: " << gplanner::terminal_text(knn_notice) << "\n";
  }
  options.should_stop = [] { return interrupted(); };
  const bool terminal = isatty(STDERR_FILENO);
  options.progress = progress_printer(terminal);

  const bool with_roadmap =
      request.load || !request.save.empty() || request.milestones || request.html_roadmap;
  gplanner::ChosenPlanner planner(scene, checker.get(), neighbors.get(), request.planner,
                                  with_roadmap, options);
  if (request.load)
    planner.roadmap_planner()->set_roadmap(gplanner::load_roadmap(scene, *request.load));
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
  write("--save-roadmap",
        [&] { gplanner::save_roadmap(planner.roadmap_planner()->roadmap(), scene, request.save); });
  if (result.solved) {
    write("--out", [&] {
      gplanner::write_path_file(request.out, scene, result, gplanner::planner_name(planner.used()),
                                checker->backend());
    });
    write("--picture", [&] { gplanner::write_path_picture(request.picture, scene, result.path); });
    write("--html", [&] {
      std::ostringstream summary;
      summary << gplanner::planner_name(planner.used()) << " on the " << checker->backend()
              << " backend, seed " << options.seed << ": "
              << result.path.size() / scene.space.width() << " waypoints, length "
              << std::setprecision(4) << result.length << ", planned in " << std::setprecision(3)
              << result.times.total << " s";
      std::string notice;
      const gplanner::RoadmapPlanner* roadmap_planner = planner.roadmap_planner();
      gplanner::write_path_viewer(
          request.html, scene, result.path, summary.str(), &notice,
          request.html_roadmap && roadmap_planner ? &roadmap_planner->roadmap() : nullptr);
      if (!notice.empty()) std::cerr << "notice: " << gplanner::terminal_text(notice) << "\n";
    });
  }
  if (interrupted()) return report_interruption(written, unwritten);

  PlanReport report;
  report.scene_file = request.scene_file;
  report.scene_name = scene.name;
  report.dof = scene.space.dof();
  report.width = scene.space.width();
  report.planner = gplanner::planner_name(planner.used());
  report.planner_asked = gplanner::planner_name(request.planner);
  report.planner_reason = planner.reason();
  report.backend = checker->backend();
  report.knn = neighbors ? neighbors->device() : "host";
  report.edges = gplanner::edge_checks_name(options.edges);
  report.certified_path = options.certify_path || options.edges == gplanner::EdgeChecks::kCertified;
  report.final_check_refinement = options.final_check_refinement;
  report.seed = options.seed;
  report.result = result;
  report.setup_s = setup_s;
  report.written = written;
  std::cout << report.text();
  if (request.json) std::cout << json_line(report.json());
  if (!result.solved) return report_no_path(request, result, options.time_limit_s, unwritten);
  return 0;
}

}  // namespace gplan
