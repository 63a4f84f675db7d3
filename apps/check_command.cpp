#include "check_command.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>

#include "check_report.h"
#include "command_line.h"
#include "gplanner/common/parallel_for.h"
#include "gplanner/common/physical_memory.h"
#include "gplanner/planner/checkers/checker_comparison.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/collision_report.h"
#include "gplanner/planner/checkers/gpu_checker.h"
#include "gplanner/planner/output/atomic_file.h"
#include "gplanner/planner/output/output_paths.h"
#include "gplanner/planner/output/path_viewer.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/planning/timed_batch_size.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "interruption.h"
#include "json_line.h"
#include "view_command.h"

namespace gplan {
namespace {

using Clock = std::chrono::steady_clock;

// Most configurations one check may ask for (then bounded by memory).
constexpr unsigned long long kMaxRows = 1000000000;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Checks the batch in slices so that a long run on the CPU shows how far it has come
// and stops soon after SIGINT or SIGTERM (interrupted(); the verdicts are then
// incomplete). The GPU answers a whole batch faster than a progress line would be read,
// and slicing would cost it parallelism.
void check_with_progress(gplanner::CollisionChecker* checker, const std::vector<float>& q,
                         std::size_t n, std::size_t width, std::vector<std::uint8_t>* verdicts) {
  const bool gpu = checker->backend() == "gpu";
  const bool show = isatty(STDERR_FILENO) && n >= 20000 && !gpu;
  // Slices of about 0.1 s on the CPU, sized from the measured rate (the first 4,096
  // configurations): soon enough for a stop, large enough that the threads stay busy;
  // with progress shown, at most a twentieth of the batch.
  const std::size_t most = std::max<std::size_t>(1, show ? n / 20 : n);
  gplanner::TimedBatchSize slice_size(0.1, std::min<std::size_t>(4096, most),
                                      std::min<std::size_t>(256, most), most);
  for (std::size_t begin = 0; begin < n && !interrupted();) {
    const std::size_t count = gpu ? n : std::min(slice_size.next(), n - begin);
    const auto slice_start = Clock::now();
    checker->check(q.data() + begin * width, count, verdicts->data() + begin);
    slice_size.record(count, seconds_since(slice_start));
    begin += count;
    if (show) {
      std::cerr << "\rchecking: " << (100 * begin / n) << "% (" << begin << " of " << n << ")"
                << std::flush;
    }
  }
  if (show) std::cerr << "\r" << std::string(40, ' ') << "\r";
}

// The checker for a --backend or --compare name, with its notice (a fallback) printed.
std::unique_ptr<gplanner::CollisionChecker> make_checker(const gplanner::Scene& scene,
                                                         const std::string& option,
                                                         const std::string& backend,
                                                         const gplanner::CheckerOptions& options) {
  std::string notice;
  try {
    auto checker = gplanner::make_collision_checker(scene, backend, options, &notice);
    if (!notice.empty()) std::cerr << "notice: " << gplanner::terminal_text(notice) << "\n";
    return checker;
  } catch (const std::invalid_argument& e) {
    throw UsageError("--" + option + ": " + e.what());
  }
}

double check_timed(gplanner::CollisionChecker* checker, const std::vector<float>& q, std::size_t n,
                   std::size_t width, std::vector<std::uint8_t>* verdicts) {
  const auto start = Clock::now();
  check_with_progress(checker, q, n, width, verdicts);
  return seconds_since(start);
}

// The GPU's figures of a checker's last call, where it is a GPU checker.
std::optional<GpuCallReport> gpu_call(gplanner::CollisionChecker* checker) {
  auto* gpu = dynamic_cast<gplanner::GpuChecker*>(checker);
  if (gpu == nullptr) return std::nullopt;
  return GpuCallReport{gpu->device_name(), gplanner::traversal_name(gpu->traversal()),
                       gpu->last_stats()};
}

// What `gplan check` was asked, read from its arguments and checked before any work.
struct CheckRequest {
  std::string scene_file;
  std::size_t n = 0;
  unsigned long long seed = 1;
  std::string backend, compare;
  std::size_t repeat = 1;
  gplanner::CheckerOptions options;
  bool has_out = false;  // --out FILE given
  std::string out;
  bool pairs = false, json = false;
  std::string html;  // --html FILE: the first colliding rows in the 3-D viewer
};

CheckRequest read_check_request(int argc, char** argv) {
  const CommandLine args(argc, argv, 2,
                         {"n", "seed", "backend", "traversal", "compare", "threads",
                          "memory-cap-mb", "small-batch", "device", "out", "repeat", "html"},
                         {"json", "pairs"});
  if (args.positionals().size() != 1)
    throw UsageError("gplan check takes one scene file, not " +
                     std::to_string(args.positionals().size()) + "; give exactly one");
  CheckRequest r;
  r.scene_file = args.positionals()[0];
  // Counts within ranges that keep the run feasible; --n's memory is checked once the
  // scene gives the row width.
  r.n = args.count("n", 10000, 1, kMaxRows);
  r.seed = args.count("seed", 1, 0, ~0ULL);
  r.backend = args.text("backend", "fcl");
  r.compare = args.text("compare", "");
  r.repeat = args.count("repeat", 1, 1, 1000);
  r.options.threads = static_cast<int>(args.count("threads", 0, 0, gplanner::kMaxThreads));
  r.options.gpu.memory_cap_bytes = args.count("memory-cap-mb", 0, 0, 1ULL << 24) << 20;
  // gplan check times the GPU's traversal: no call is answered on the host, whatever
  // its size (the planners' gpu backend routes small calls there).
  r.options.gpu.host_calls_up_to = 0;
  if (args.has("small-batch"))
    r.options.gpu.warp_per_pair_up_to = args.count("small-batch", 0, 0, kMaxRows);
  if (args.has("traversal") &&
      !gplanner::parse_traversal(args.text("traversal", ""), &r.options.gpu.traversal)) {
    throw UsageError("--traversal: '" + args.text("traversal", "") +
                     "' is not one of basic, packet, balanced");
  }
  // The GPU's settings change nothing on the other backends: say so rather than ignore
  // them (a memory cap meant to be tested would go untested).
  r.options.gpu.device = args.gpu_device(0);
  for (const char* gpu_only : {"traversal", "memory-cap-mb", "small-batch", "device"}) {
    if (args.has(gpu_only) && r.backend != "gpu" && r.compare != "gpu") {
      throw UsageError(std::string("--") + gpu_only +
                       " applies to the gpu backend only; add --backend gpu or --compare gpu");
    }
  }
  r.has_out = args.has("out");
  r.out = args.text("out", "");
  r.pairs = args.flag("pairs");
  r.json = args.flag("json");
  if (r.pairs && !r.has_out)
    throw UsageError("--pairs adds the colliding pair to each row of --out FILE; add --out");
  r.html = args.text("html", "");
  if (args.has("html") && r.html.empty()) throw UsageError("--html: give a file name");
  if (args.has("html")) require_path_viewer();
  return r;
}

// Refuses a batch whose rows would take more than half of the machine's memory.
void check_batch_fits(std::size_t n, std::size_t width) {
  // The batch, its verdicts and one run's verdicts.
  const double batch_bytes = static_cast<double>(n) * (width * sizeof(float) + 2);
  if (gplanner::fits_in_memory(batch_bytes)) return;
  throw UsageError(
      "--n " + std::to_string(n) + ": " + std::to_string(width) + "-float rows need about " +
      gplanner::memory_text(batch_bytes) + ", more than half of this machine's " +
      gplanner::memory_text(gplanner::physical_memory_bytes()) + " of memory; give a smaller --n");
}

// The report's description of the scene.
void describe_scene(const std::string& scene_file, const gplanner::Scene& scene,
                    CheckReport* report) {
  report->scene_file = scene_file;
  report->scene_name = scene.name;
  report->robot_name = scene.robot.name;
  report->links = scene.robot.links.size();
  report->robot_triangles = scene.robot.triangle_count();
  report->checked_pairs = scene.robot.checked_pairs().size();
  report->base = gplanner::base_type_name(scene.space.base);
  report->dof = scene.space.dof();
  report->width = scene.space.width();
  report->obstacles = scene.obstacles.size();
  report->obstacle_triangles = scene.obstacle_triangle_count();
  report->dropped_obstacle_triangles = scene.dropped_obstacle_triangles;
  report->delta = gplanner::tolerance_delta(scene);
}

// Checks the batch `repeat` times (the first run pays for allocations a planner makes
// once) and returns the median time; every run must give the same verdicts. False when
// interrupted.
bool check_repeated(gplanner::CollisionChecker* checker, const std::vector<float>& q, std::size_t n,
                    std::size_t width, std::size_t repeat, std::vector<std::uint8_t>* verdicts,
                    double* median_s) {
  std::vector<double> run_s;
  for (std::size_t r = 0; r < repeat; ++r) {
    std::vector<std::uint8_t> run_verdicts(n);
    run_s.push_back(check_timed(checker, q, n, width, &run_verdicts));
    if (interrupted()) return false;
    if (r > 0 && run_verdicts != *verdicts)
      throw std::runtime_error("the " + checker->backend() +
                               " backend gave different verdicts for the same batch");
    verdicts->swap(run_verdicts);
  }
  std::sort(run_s.begin(), run_s.end());
  *median_s = run_s[run_s.size() / 2];
  return true;
}

// Rows shown by --html: the first colliding ones.
constexpr std::size_t kViewedRows = 50;

// The pair FCL finds colliding (CollisionReporter) at each of the first `most` colliding
// rows, by row (free rows and those past `most`: none). False when interrupted.
bool find_colliding_pairs(const gplanner::Scene& scene, const std::vector<float>& q,
                          const std::vector<std::uint8_t>& verdicts, std::size_t most,
                          std::vector<std::optional<gplanner::CollisionPair>>* pairs) {
  const std::size_t width = scene.space.width();
  pairs->assign(verdicts.size(), std::nullopt);
  if (most == 0) return true;
  gplanner::CollisionReporter reporter(scene);
  std::size_t found = 0;
  for (std::size_t i = 0; i < verdicts.size() && found < most; ++i) {
    if (!verdicts[i]) continue;
    if (interrupted()) return false;
    (*pairs)[i] = reporter.first_pair(&q[i * width]);
    ++found;
  }
  return true;
}

// --pairs: per row, its pair (a link, then an obstacle's key or a second link), "- -" for a
// free row; a colliding row where no surfaces meet (inside a closed body, or within the
// band) gets the closest pair and "(no-contact)".
std::vector<std::string> pair_columns_of(
    const std::vector<std::optional<gplanner::CollisionPair>>& pairs) {
  std::vector<std::string> columns(pairs.size(), "- -");
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (!pairs[i]) continue;
    columns[i] = pairs[i]->a_key + " " + pairs[i]->b_key + (pairs[i]->found ? "" : " (no-contact)");
  }
  return columns;
}

// --html: the first kViewedRows colliding rows in the 3-D viewer, each with its pair
// (`pairs`, found for them) drawn red and named; where none collides, the first row.
void write_colliding_rows_viewer(const std::string& html, const gplanner::Scene& scene,
                                 const std::vector<float>& q,
                                 const std::vector<std::uint8_t>& verdicts,
                                 const std::vector<std::optional<gplanner::CollisionPair>>& pairs) {
  const std::size_t width = scene.space.width();
  const gplanner::RobotModel& robot = scene.robot;
  auto link_index = [&](const std::string& name) {
    for (std::size_t l = 0; l < robot.links.size(); ++l)
      if (robot.links[l].name == name) return static_cast<int>(l);
    return -1;
  };
  std::vector<float> rows;
  std::vector<gplanner::ViewedRow> viewed;
  std::size_t colliding = 0;
  for (std::size_t i = 0; i < verdicts.size(); ++i) colliding += verdicts[i];
  for (std::size_t i = 0; i < verdicts.size() && viewed.size() < kViewedRows; ++i) {
    if (!pairs[i]) continue;
    const gplanner::CollisionPair& pair = *pairs[i];
    gplanner::ViewedRow row;
    row.label = "row " + std::to_string(i) + ", " + pair.describe();
    row.link = link_index(pair.a_key);
    unsigned obstacle = 0;
    if (std::sscanf(pair.b_key.c_str(), "obstacles[%u]", &obstacle) == 1) {
      row.obstacle = static_cast<int>(obstacle);
    } else {
      row.other_link = link_index(pair.b_key);
    }
    rows.insert(rows.end(), &q[i * width], &q[(i + 1) * width]);
    viewed.push_back(row);
  }
  if (viewed.empty()) {
    rows.assign(q.begin(), q.begin() + width);
    viewed.push_back(
        {"row 0: free, as all " + std::to_string(verdicts.size()) + " rows are", -1, -1, -1});
  }
  std::string notice;
  gplanner::write_rows_viewer(html, scene, rows, viewed,
                              std::to_string(colliding) + " of " + std::to_string(verdicts.size()) +
                                  " rows collide; the first " +
                                  std::to_string(std::min(colliding, kViewedRows)) +
                                  " shown, what collides in red",
                              &notice);
  if (!notice.empty()) std::cerr << "notice: " << gplanner::terminal_text(notice) << "\n";
}

// --out: each configuration's values as the scene file gives them (world or plane
// positions, not relative to the scene frame), summed in double, then its verdict and
// (--pairs) its pair; far from the origin (the frame moved) with all of a double's
// digits, since nine would not place a position within the band.
void write_verdict_file(const std::string& out, const gplanner::Scene& scene,
                        const std::vector<float>& q, const std::vector<std::uint8_t>& verdicts,
                        const std::vector<std::string>& pair_columns) {
  const gplanner::ConfigurationSpace& space = scene.space;
  const std::size_t width = space.width();
  const int position_precision = scene.p_WS.isZero() ? 9 : 17;
  std::vector<double> values(width);
  gplanner::write_file_atomically(out, [&](std::ostream& stream) {
    for (std::size_t i = 0; i < verdicts.size(); ++i) {
      space.to_file_values(&q[i * width], values.data());
      for (std::size_t k = 0; k < width; ++k) {
        const bool position = static_cast<int>(k) < space.position_width();
        stream << std::setprecision(position ? position_precision : 9)
               << (position ? values[k] : q[i * width + k]) << ' ';
      }
      stream << int(verdicts[i]);
      if (!pair_columns.empty()) stream << ' ' << pair_columns[i];
      stream << '\n';
    }
  });
}

}  // namespace

int run_check(int argc, char** argv) {
  const CheckRequest request = read_check_request(argc, argv);
  catch_interruptions();
  // Refuse an output file that cannot be written before doing the work, not after
  // (gplanner::check_output_paths): against the scene file, then every file it loads.
  std::vector<gplanner::NamedFile> outputs;
  if (request.has_out) outputs.push_back({"--out", request.out});
  if (!request.html.empty()) outputs.push_back({"--html", request.html});
  std::vector<gplanner::NamedFile> inputs{{"the scene file", request.scene_file}};
  gplanner::check_output_paths(outputs, inputs);
  std::vector<std::string> unwritten;
  for (const gplanner::NamedFile& output : outputs)
    unwritten.push_back(output.name + " " + output.path);

  const auto load_start = Clock::now();
  const gplanner::Scene scene = gplanner::load_scene(request.scene_file);
  for (const std::string& notice : scene.notices)
    std::cerr << "notice: " << gplanner::terminal_text(notice) << "\n";
  for (const std::string& file : scene.input_files)
    inputs.push_back({"a file the scene loads", file});
  gplanner::check_output_paths(outputs, inputs);
  if (interrupted()) return report_interruption({}, unwritten);
  CheckReport report;
  report.load_s = seconds_since(load_start);
  describe_scene(request.scene_file, scene, &report);
  const std::size_t n = request.n, width = scene.space.width();
  check_batch_fits(n, width);

  std::unique_ptr<gplanner::CollisionChecker> checker =
      make_checker(scene, "backend", request.backend, request.options);
  gplanner::check_start_and_goal(scene, checker.get());
  report.straight_line_collision = gplanner::first_collision_on_straight_line(scene, checker.get());
  report.backend = checker->backend();
  report.n = n;
  report.seed = request.seed;
  report.repeat = request.repeat;

  std::vector<float> q(n * width);
  std::mt19937_64 rng(request.seed);
  for (std::size_t i = 0; i < n; ++i) scene.space.sample_uniform(&rng, &q[i * width]);
  std::vector<std::uint8_t> verdicts(n);
  if (!check_repeated(checker.get(), q, n, width, request.repeat, &verdicts, &report.seconds))
    return report_interruption({}, unwritten);
  for (const std::uint8_t v : verdicts) report.collisions += v;
  report.gpu = gpu_call(checker.get());

  // --compare: the same configurations through a second backend, every disagreement
  // judged by FCL's verdict and distance against the band.
  if (!request.compare.empty()) {
    std::unique_ptr<gplanner::CollisionChecker> other =
        make_checker(scene, "compare", request.compare, request.options);
    CheckReport::Compare& c = report.compare.emplace();
    c.backend = other->backend();
    std::vector<std::uint8_t> other_verdicts(n);
    c.seconds = check_timed(other.get(), q, n, width, &other_verdicts);
    if (interrupted()) return report_interruption({}, unwritten);
    gplanner::FclChecker judge(scene, request.options.threads);
    c.comparison = gplanner::compare_verdicts(q.data(), n, width, verdicts.data(),
                                              other_verdicts.data(), &judge, report.delta);
    c.gpu = gpu_call(other.get());
  }

  // The colliding pairs, found once for both outputs: every colliding row's for --pairs,
  // the first kViewedRows' for --html.
  std::vector<std::optional<gplanner::CollisionPair>> pairs;
  const std::size_t most = request.pairs ? n : request.html.empty() ? 0 : kViewedRows;
  if (!find_colliding_pairs(scene, q, verdicts, most, &pairs))
    return report_interruption({}, unwritten);
  if (!request.out.empty()) {
    if (interrupted()) return report_interruption({}, unwritten);
    write_verdict_file(request.out, scene, q, verdicts,
                       request.pairs ? pair_columns_of(pairs) : std::vector<std::string>{});
    report.written = request.out;
  }
  if (!request.html.empty()) {
    if (interrupted()) {
      return report_interruption(report.written.empty()
                                     ? std::vector<std::string>{}
                                     : std::vector<std::string>{"--out " + report.written},
                                 {"--html " + request.html});
    }
    write_colliding_rows_viewer(request.html, scene, q, verdicts, pairs);
  }
  std::cout << report.text();
  if (!request.html.empty())
    std::cout << "wrote       --html " << gplanner::terminal_text(request.html) << "\n";
  if (request.json) std::cout << json_line(report.json());
  // A comparison that finds the band broken fails the run, so scripts notice.
  if (report.band_broken()) {
    std::cerr << "gplan: the checkers disagree outside the tolerance band\n";
    return 3;
  }
  return 0;
}

}  // namespace gplan
