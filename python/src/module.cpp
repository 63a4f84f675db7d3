// The Python module `gplanner` (its package's _core): scenes, batch checks and plans
// from numpy, over the same library gplan runs. The package's __init__.py re-exports
// it; python/README.md documents it, python/tests tests it.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "arrays.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/checkers/gpu_checker.h"
#include "gplanner/planner/planning/certified_motions.h"
#include "gplanner/planner/planning/local_planner.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/path_recheck.h"
#include "gplanner/planner/planning/plan_options.h"
#include "gplanner/planner/planning/planner_choice.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/planning/timed_batch_size.h"
#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/version.h"
#include "interrupts.h"

namespace py = pybind11;

namespace gplanner::python {
namespace {

// Rows per checker call in a long check: sized to take about kSliceSeconds, so that
// Ctrl-C is seen between calls, and starting large enough (2^17) that a batch of
// 100,000 is one call, as in C++.
constexpr double kSliceSeconds = 0.2;

py::array_t<float> rows_array(const float* data, std::size_t n, int width) {
  py::array_t<float> a({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(width)});
  std::copy_n(data, n * width, a.mutable_data());
  return a;
}

py::array_t<float> row_array(const std::vector<float>& row) {
  py::array_t<float> a(static_cast<py::ssize_t>(row.size()));
  std::copy(row.begin(), row.end(), a.mutable_data());
  return a;
}

struct PyPlanResult {
  bool solved = false;
  py::array_t<float> path;  // shape [waypoints, width]
  py::dict stats;           // gplan plan --json's fields
};

class PyChecker {
 public:
  PyChecker(std::shared_ptr<const Scene> scene, const std::string& backend, int threads, int device)
      : scene_(std::move(scene)), options_(plan_options(*scene_)) {
    CheckerOptions options;
    options.threads = threads;
    options.gpu.device = device;
    {
      py::gil_scoped_release release;  // builds BVHs and times the GPU's calls
      checker_ = make_collision_checker(*scene_, backend, options, &notice_);
    }
    local_ = std::make_unique<LocalPlanner>(*scene_, checker_.get(), options_.local);
    certified_ = std::make_unique<CertifiedMotions>(*scene_, checker_.get(), options_.certified);
  }

  std::string backend() const { return checker_->backend(); }
  const std::string& notice() const { return notice_; }
  std::size_t device_calls() const { return checker_->device_calls(); }
  std::vector<int> devices() const {
    const auto* gpu = dynamic_cast<const GpuChecker*>(checker_.get());
    return gpu ? gpu->devices() : std::vector<int>{};
  }

  py::array_t<bool> check(py::handle q) {
    const Rows rows = rows_of(q, scene_->space.width(), "q");
    std::uint8_t* verdicts = nullptr;
    py::array_t<bool> out = new_verdicts(rows.n, &verdicts);
    const std::size_t width = scene_->space.width();
    InterruptPoll poll;
    {
      py::gil_scoped_release release;
      TimedBatchSize batch(kSliceSeconds, std::size_t(1) << 17, 1024, std::size_t(1) << 24);
      for (std::size_t first = 0, n = 0; first < rows.n; first += n) {
        if (first > 0 && poll.raised()) break;
        n = std::min(batch.next(), rows.n - first);
        const auto started = std::chrono::steady_clock::now();
        checker_->check(rows.data + first * width, n, verdicts + first);
        batch.record(
            n, std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
      }
    }
    poll.rethrow();
    return out;
  }

  // For benchmarks/programs/python_overhead.py: the seconds of each of `repeat` calls of
  // the C++ checker on the same rows, timed in C++ (no Python between the clocks).
  std::vector<double> check_seconds(py::handle q, int repeat) {
    const Rows rows = rows_of(q, scene_->space.width(), "q");
    std::vector<std::uint8_t> verdicts(rows.n);
    std::vector<double> seconds;
    py::gil_scoped_release release;
    for (int r = 0; r < repeat; ++r) {
      const auto started = std::chrono::steady_clock::now();
      checker_->check(rows.data, rows.n, verdicts.data());
      seconds.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
    }
    return seconds;
  }

  py::array_t<bool> check_motions(py::handle a, py::handle b, bool certified) {
    const int width = scene_->space.width();
    const Rows from = rows_of(a, width, "a"), to = rows_of(b, width, "b");
    if (from.n != to.n) {
      throw py::value_error("a and b: as many rows each expected, got " + std::to_string(from.n) +
                            " and " + std::to_string(to.n));
    }
    std::uint8_t* invalid = nullptr;
    py::array_t<bool> out = new_verdicts(from.n, &invalid);
    MotionChecker* motions = certified ? static_cast<MotionChecker*>(certified_.get())
                                       : static_cast<MotionChecker*>(local_.get());
    InterruptPoll poll;
    {
      py::gil_scoped_release release;
      constexpr std::size_t kPart = 4096;  // motions between looks at Ctrl-C
      for (std::size_t first = 0; first < from.n; first += kPart) {
        if (first > 0 && poll.raised()) break;
        const std::size_t n = std::min(kPart, from.n - first);
        motions->check_motions(from.data + first * width, to.data + first * width, n,
                               invalid + first);
      }
    }
    poll.rethrow();
    return out;
  }

  PyPlanResult plan(const std::string& planner, py::object seed, py::object time_limit,
                    py::object milestones) {
    PlannerKind kind;
    if (!parse_planner(planner, &kind))
      throw py::value_error("planner: '" + planner + "' is not one of " + planner_names());
    PlanOptions options = options_;
    if (!seed.is_none()) options.seed = seed.cast<unsigned long long>();
    if (!time_limit.is_none()) {
      options.time_limit_s = time_limit.cast<double>();
      if (!(options.time_limit_s > 0))
        throw py::value_error("time_limit: a positive number of seconds expected");
    }
    if (!milestones.is_none()) {
      const long long m = milestones.cast<long long>();
      if (m < 1) throw py::value_error("milestones: at least 1 expected");
      if (!keeps_roadmap(kind))
        throw py::value_error("milestones: for the roadmap planners, not for " + planner);
      options.milestones = static_cast<std::size_t>(m);
    }
    InterruptPoll poll;
    options.should_stop = [&poll] { return poll.raised(); };
    PlanResult result;
    std::string knn, reason;
    PlannerKind used = kind;
    {
      py::gil_scoped_release release;
      check_start_and_goal(*scene_, checker_.get());
      const std::unique_ptr<NeighborFinder> neighbors =
          make_neighbor_finder(make_metric(scene_->space, scene_->planner), checker_->backend(),
                               nullptr, checker_->gpu_device());
      knn = neighbors->device();
      ChosenPlanner chosen(*scene_, checker_.get(), neighbors.get(), kind,
                           /*with_roadmap=*/!milestones.is_none(), options);
      result = chosen.solve(scene_->start.data(), scene_->goal.data());
      used = chosen.used();
      reason = chosen.reason();
    }
    poll.rethrow();
    const int width = scene_->space.width();
    PyPlanResult out;
    out.solved = result.solved;
    out.path = rows_array(result.path.data(), result.path.size() / width, width);
    const PlanTimes& t = result.times;
    const PlanGpuCalls& c = result.gpu_calls;
    py::dict times, calls;
    times["sampling"] = t.sampling;
    times["state_checks"] = t.state_checks;
    times["knn"] = t.knn;
    times["search"] = t.search;
    times["edge_checks"] = t.edge_checks;
    times["shortcutting"] = t.shortcutting;
    calls["state_checks"] = c.state_checks;
    calls["knn"] = c.knn;
    calls["search"] = c.search;
    calls["edge_checks"] = c.edge_checks;
    calls["shortcutting"] = c.shortcutting;
    calls["total"] = c.total;
    py::dict& s = out.stats;
    s["planner"] = planner_name(used);
    s["planner_asked"] = planner_name(kind);
    s["planner_reason"] = reason;
    s["backend"] = checker_->backend();
    s["knn"] = knn;
    s["edge_checks"] = edge_checks_name(options.edges);
    s["path_check"] =
        options.certify_path || options.edges == EdgeChecks::kCertified ? "certified" : "fine";
    s["seed"] = options.seed;
    s["solved"] = result.solved;
    s["stop_reason"] = result.stop_reason;
    s["length"] = result.length;
    s["length_before_shortcut"] = result.length_before_shortcut;
    s["waypoints"] = result.path.size() / width;
    s["milestones"] = result.milestones;
    s["edges"] = result.edges;
    s["edges_checked"] = result.edges_checked;
    s["states_checked"] = result.states_checked;
    s["samples_checked"] = result.samples_checked;
    s["searches"] = result.searches;
    s["edge_batches"] = result.edge_batches;
    s["rounds"] = result.rounds;
    s["seconds"] = t.total;
    s["times"] = times;
    s["gpu_calls"] = calls;
    return out;
  }

 private:
  std::shared_ptr<const Scene> scene_;
  PlanOptions options_;
  std::string notice_;
  std::unique_ptr<CollisionChecker> checker_;
  std::unique_ptr<LocalPlanner> local_;
  std::unique_ptr<CertifiedMotions> certified_;
};

std::shared_ptr<const Scene> load(const std::string& path) {
  py::gil_scoped_release release;
  return std::make_shared<const Scene>(load_scene(path));
}

// Scene.checker's device: a CUDA device number, or "all" (GpuCheckerOptions::kAllDevices).
int device_number(py::handle device) {
  if (py::isinstance<py::str>(device) && device.cast<std::string>() == "all")
    return GpuCheckerOptions::kAllDevices;
  if (py::isinstance<py::int_>(device) && !py::isinstance<py::bool_>(device)) {
    const long long d = device.cast<long long>();
    if (d >= 0 && d < 10000) return static_cast<int>(d);
  }
  throw py::value_error("device: a CUDA device number (0, 1, ...) or \"all\", not " +
                        py::repr(device).cast<std::string>());
}

py::array_t<float> sample(const Scene& scene, long long n, unsigned long long seed) {
  if (n < 0) throw py::value_error("n: a count of configurations (0 or more) expected");
  const int width = scene.space.width();
  py::array_t<float> q({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(width)});
  float* data = q.mutable_data();
  // As gplan check --n N --seed S draws its rows.
  std::mt19937_64 rng(seed);
  for (long long i = 0; i < n; ++i) scene.space.sample_uniform(&rng, data + i * width);
  return q;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "gplanner: exact triangle-mesh collision checks and plans, batched on the GPU";
  m.attr("__version__") = version();  // the libgplanner loaded
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);

  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene")
      .def_property_readonly("name", [](const Scene& s) { return s.name; })
      .def_property_readonly("file", [](const Scene& s) { return s.file; })
      .def_property_readonly("width", [](const Scene& s) { return s.space.width(); })
      .def_property_readonly("dof", [](const Scene& s) { return s.space.dof(); })
      .def_property_readonly("start", [](const Scene& s) { return row_array(s.start); })
      .def_property_readonly("goal", [](const Scene& s) { return row_array(s.goal); })
      .def_property_readonly("frame_origin",
                             [](const Scene& s) {
                               return std::vector<double>{s.p_WS.x(), s.p_WS.y(), s.p_WS.z()};
                             })
      .def_property_readonly("notices", [](const Scene& s) { return s.notices; })
      .def("sample", &sample, py::arg("n"), py::arg("seed") = 1)
      .def(
          "checker",
          [](const std::shared_ptr<Scene>& s, const std::string& backend, int threads,
             py::handle device) {
            return std::make_unique<PyChecker>(s, backend, threads, device_number(device));
          },
          py::arg("backend") = "gpu", py::arg("threads") = 0, py::arg("device") = 0)
      .def(
          "recheck",
          [](const Scene& s, py::handle path, double refinement) {
            const Rows rows = rows_of(path, s.space.width(), "path");
            const std::vector<float> p(rows.data, rows.data + rows.n * s.space.width());
            py::gil_scoped_release release;
            return path_recheck_problem(s, p, refinement, /*from_start_to_goal=*/true);
          },
          py::arg("path"), py::arg("refinement") = 10.0)
      .def("__repr__", [](const Scene& s) {
        return "<gplanner.Scene '" + s.name + "', " + std::to_string(s.space.dof()) + " DOF>";
      });

  py::class_<PyChecker>(m, "Checker")
      .def_property_readonly("backend", &PyChecker::backend)
      .def_property_readonly("notice", &PyChecker::notice)
      .def_property_readonly("device_calls", &PyChecker::device_calls)
      .def_property_readonly("devices", &PyChecker::devices)
      .def("check", &PyChecker::check, py::arg("q"))
      .def("_check_seconds", &PyChecker::check_seconds, py::arg("q"), py::arg("repeat"))
      .def("check_motions", &PyChecker::check_motions, py::arg("a"), py::arg("b"),
           py::arg("certified") = true)
      .def("plan", &PyChecker::plan, py::arg("planner") = "auto", py::arg("seed") = py::none(),
           py::arg("time_limit") = py::none(), py::arg("milestones") = py::none())
      .def("__repr__",
           [](const PyChecker& c) { return "<gplanner.Checker on " + c.backend() + ">"; });

  py::class_<PyPlanResult>(m, "PlanResult")
      .def_readonly("solved", &PyPlanResult::solved)
      .def_readonly("path", &PyPlanResult::path)
      .def_readonly("stats", &PyPlanResult::stats)
      .def("__repr__", [](const PyPlanResult& r) {
        return std::string("<gplanner.PlanResult ") + (r.solved ? "solved" : "not solved") + ">";
      });

  m.def("load_scene", &load, py::arg("path"));
}

}  // namespace gplanner::python
