#include "check_command.h"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

#include "command_line.h"
#include "gplanner/planner/atomic_file.h"
#include "gplanner/planner/checker_factory.h"
#include "gplanner/planner/scene.h"

namespace gplan {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string json_string(const std::string& text) {
  std::ostringstream out;
  out << '"';
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out << '\\' << c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out << "\\u" << std::hex << std::setw(4) << std::setfill('0') << static_cast<int>(c)
          << std::dec;
    } else {
      out << c;
    }
  }
  out << '"';
  return out.str();
}

// Checks the batch in slices so that a long run shows how far it has come.
void check_with_progress(gplanner::CollisionChecker* checker, const std::vector<float>& q,
                         std::size_t n, std::size_t width, std::vector<std::uint8_t>* verdicts) {
  const bool show = isatty(STDERR_FILENO) && n >= 20000;
  const std::size_t slices = show ? 20 : 1;
  const std::size_t slice = (n + slices - 1) / slices;
  for (std::size_t begin = 0; begin < n; begin += slice) {
    const std::size_t count = std::min(slice, n - begin);
    checker->check(q.data() + begin * width, count, verdicts->data() + begin);
    if (show) {
      std::cerr << "\rchecking: " << (100 * (begin + count) / n) << "% (" << begin + count
                << " of " << n << ")" << std::flush;
    }
  }
  if (show) std::cerr << "\r" << std::string(40, ' ') << "\r";
}

}  // namespace

int run_check(int argc, char** argv) {
  const CommandLine args(argc, argv, 2, {"n", "seed", "backend", "threads", "out"}, {"json"});
  if (args.positionals().size() != 1) throw UsageError("gplan check takes one scene file");
  const std::string scene_file = args.positionals()[0];
  const std::size_t n = static_cast<std::size_t>(args.count("n", 10000));
  const unsigned long long seed = static_cast<unsigned long long>(args.count("seed", 1));
  const std::string backend = args.text("backend", "fcl");
  gplanner::CheckerOptions options;
  options.threads = static_cast<int>(args.count("threads", 0));

  // Refuse an output file that cannot be written before doing the work, not after.
  const std::string out = args.text("out", "");
  if (!out.empty()) {
    const std::filesystem::path folder = std::filesystem::path(out).parent_path();
    if (std::filesystem::is_directory(out) ||
        !std::filesystem::is_directory(folder.empty() ? "." : folder)) {
      throw UsageError("--out " + out + ": not a file in an existing folder");
    }
  }

  const auto load_start = Clock::now();
  const gplanner::Scene scene = gplanner::load_scene(scene_file);
  for (const std::string& notice : scene.notices) std::cerr << "notice: " << notice << "\n";
  const double load_s = seconds_since(load_start);
  const gplanner::ConfigurationSpace& space = scene.space;
  const std::size_t width = space.width();
  const auto pairs = scene.robot.checked_pairs();

  std::unique_ptr<gplanner::CollisionChecker> checker;
  try {
    checker = gplanner::make_collision_checker(scene, backend, options);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--backend: ") + e.what());
  }
  gplanner::check_start_and_goal(scene, checker.get());
  const double line_collision = gplanner::first_collision_on_straight_line(scene, checker.get());

  std::vector<float> q(n * width);
  std::mt19937_64 rng(seed);
  for (std::size_t i = 0; i < n; ++i) space.sample_uniform(&rng, &q[i * width]);
  std::vector<std::uint8_t> verdicts(n);
  const auto check_start = Clock::now();
  check_with_progress(checker.get(), q, n, width, &verdicts);
  const double check_s = seconds_since(check_start);
  std::size_t collisions = 0;
  for (const std::uint8_t v : verdicts) collisions += v;
  const double fraction = n ? static_cast<double>(collisions) / n : 0.0;
  const double rate = check_s > 0 ? n / check_s : 0.0;

  std::cout << "scene       " << scene_file << " (" << scene.name << "), loaded in "
            << std::fixed << std::setprecision(3) << load_s << " s\n"
            << "robot       " << scene.robot.name << ": " << scene.robot.links.size()
            << " links, " << scene.robot.triangle_count() << " triangles, " << pairs.size()
            << " checked link pairs; " << gplanner::base_type_name(space.base) << " base, "
            << space.dof() << " DOF (" << width << " floats)\n"
            << "obstacles   " << scene.obstacles.size() << " (" << scene.obstacle_triangle_count()
            << " triangles)\n"
            << "backend     " << checker->backend() << "\n"
            << "start, goal free; straight line start -> goal ";
  if (line_collision >= 0) {
    std::cout << "collides (first at " << std::setprecision(1) << 100 * line_collision
              << "% of the way)\n";
  } else {
    std::cout << "is free\n";
  }
  std::cout << "checked     " << n << " configurations (seed " << seed << ")\n"
            << "collisions  " << collisions << " (" << std::setprecision(2) << 100 * fraction
            << "%)\n"
            << "time        " << std::setprecision(4) << check_s << " s, " << std::setprecision(0)
            << rate << " queries/s\n";

  if (!out.empty()) {
    gplanner::write_file_atomically(out, [&](std::ostream& stream) {
      stream << std::setprecision(9);
      for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k = 0; k < width; ++k) stream << q[i * width + k] << ' ';
        stream << int(verdicts[i]) << '\n';
      }
    });
    std::cout << "wrote       " << out << "\n";
  }
  if (args.flag("json")) {
    std::cout << std::setprecision(6) << "{\"scene\":" << json_string(scene_file)
              << ",\"name\":" << json_string(scene.name)
              << ",\"backend\":" << json_string(checker->backend()) << ",\"n\":" << n
              << ",\"seed\":" << seed << ",\"dof\":" << space.dof() << ",\"width\":" << width
              << ",\"links\":" << scene.robot.links.size()
              << ",\"robot_triangles\":" << scene.robot.triangle_count()
              << ",\"checked_pairs\":" << pairs.size()
              << ",\"obstacle_triangles\":" << scene.obstacle_triangle_count()
              << ",\"collisions\":" << collisions << ",\"collision_fraction\":" << fraction
              << ",\"seconds\":" << check_s << ",\"queries_per_second\":" << rate
              << ",\"straight_line_collides\":" << (line_collision >= 0 ? "true" : "false")
              << "}\n";
  }
  return 0;
}

}  // namespace gplan
