// Stability: hostile input to the batch call and the loaders.
// - A batch of zero configurations (and zero motions) is answered without touching
//   the pointers.
// - A row that is not a configuration (a NaN or infinite entry, a quaternion of zero
//   length) is reported colliding on every backend, never free and never thrown
//   about in the hot path; the rows beside it keep their verdicts.
// - Quaternions of any finite non-zero length, 1e-30 to 1e30, mean their rotation.
// - A link of one nanometre loads and is checked like any other.
// - An obstacle of two million triangles loads, builds and checks in bounded time and
//   memory, with answers known by construction.
// - Over the memory cap (gpu), batches are chunked and answer as the cpu does.

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/checker_comparison.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/checkers/gpu_checker.h"
#include "gplanner/planner/planning/local_planner.h"
#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "require_gpu.h"
#include "test_support.h"

namespace gplanner {
namespace {

const Traversal kTraversals[] = {Traversal::kBasic, Traversal::kPacket, Traversal::kBalanced};

Scene load(const std::string& name) {
  return load_scene(testing::project_root() + "/scenes/" + name);
}

std::vector<float> sample(const Scene& scene, std::size_t n, unsigned seed) {
  std::vector<float> q(n * scene.space.width());
  std::mt19937_64 rng(seed);
  for (std::size_t i = 0; i < n; ++i) scene.space.sample_uniform(&rng, &q[i * scene.space.width()]);
  return q;
}

std::vector<std::uint8_t> verdicts(CollisionChecker* checker, const std::vector<float>& q,
                                   std::size_t width) {
  const std::size_t n = q.size() / width;
  std::vector<std::uint8_t> v(n, 2);
  checker->check(q.data(), n, v.data());
  return v;
}

std::unique_ptr<CollisionChecker> checker_for(const Scene& scene, const std::string& backend,
                                              Traversal traversal = Traversal::kBalanced) {
  CheckerOptions options;
  options.gpu.traversal = traversal;
  options.gpu.host_calls_up_to = 0;  // every traversal really runs, whatever the batch
  auto checker = make_collision_checker(scene, backend, options);
  EXPECT_EQ(checker->backend(), backend) << "the backend asked for did not run";
  return checker;
}

// --- empty batches ----------------------------------------------------------------------

void expect_empty_batches(CollisionChecker* checker, const Scene& scene) {
  checker->check(nullptr, 0, nullptr);
  LocalPlanner local(scene, checker);
  EXPECT_TRUE(local.check_motions(nullptr, nullptr, 0, nullptr));
  EXPECT_EQ(local.stats().samples, 0u);
}

TEST(StabilityHostileInput, EmptyBatchesCpuAndFcl) {
  for (const char* file : {"piano.yaml", "humanoid.yaml"}) {
    const Scene scene = load(file);
    for (const char* backend : {"cpu", "fcl"})
      expect_empty_batches(checker_for(scene, backend).get(), scene);
  }
}

TEST(StabilityHostileInput, GpuEmptyBatches) {
  REQUIRE_GPU();
  const Scene scene = load("humanoid.yaml");
  for (const Traversal t : kTraversals)
    expect_empty_batches(checker_for(scene, "gpu", t).get(), scene);
}

// --- rows that are not configurations ---------------------------------------------------

// Clean rows, then copies of them with one entry made NaN, +inf or -inf (every entry
// in turn) and, for a floating base, with a zero quaternion; the copies interleaved
// with the clean rows in one batch.
void expect_non_finite_rows_collide(CollisionChecker* checker, const Scene& scene,
                                    const std::string& what) {
  const std::size_t w = scene.space.width(), n = 64;
  const std::vector<float> clean = sample(scene, n, 7);
  const std::vector<std::uint8_t> expected = verdicts(checker, clean, w);
  std::vector<float> batch;
  std::vector<int> bad;  // per row of the batch: 1 not a configuration, 0 clean row i
  std::vector<std::size_t> source;
  const float values[3] = {std::numeric_limits<float>::quiet_NaN(),
                           std::numeric_limits<float>::infinity(),
                           -std::numeric_limits<float>::infinity()};
  std::size_t next = 0;
  auto add_clean = [&] {
    const std::size_t i = next++ % n;
    batch.insert(batch.end(), &clean[i * w], &clean[(i + 1) * w]);
    bad.push_back(0);
    source.push_back(i);
  };
  for (std::size_t k = 0; k < w; ++k) {
    for (const float value : values) {
      add_clean();
      const std::size_t i = next % n;
      batch.insert(batch.end(), &clean[i * w], &clean[(i + 1) * w]);
      batch[batch.size() - w + k] = value;
      bad.push_back(1);
      source.push_back(i);
    }
  }
  if (scene.space.base == BaseType::kFloating) {
    for (int r = 0; r < 4; ++r) {
      add_clean();
      batch.insert(batch.end(), &clean[0], &clean[w]);
      std::fill(batch.end() - w + 3, batch.end() - w + 7, 0.0f);
      bad.push_back(1);
      source.push_back(0);
    }
  }
  const std::vector<std::uint8_t> got = verdicts(checker, batch, w);
  for (std::size_t r = 0; r < got.size(); ++r) {
    if (bad[r]) {
      EXPECT_EQ(got[r], 1) << what << ": row " << r << " is not a configuration, reported free";
    } else {
      EXPECT_EQ(got[r], expected[source[r]]) << what << ": clean row " << r << " changed";
    }
  }
}

TEST(StabilityHostileInput, NonFiniteRowsCollideCpuAndFcl) {
  for (const char* file : {"piano.yaml", "pr2_base_arm.yaml", "humanoid.yaml"}) {
    const Scene scene = load(file);
    for (const char* backend : {"cpu", "fcl"})
      expect_non_finite_rows_collide(checker_for(scene, backend).get(), scene,
                                     std::string(backend) + " " + file);
  }
}

TEST(StabilityHostileInput, GpuNonFiniteRowsCollide) {
  REQUIRE_GPU();
  for (const char* file : {"piano.yaml", "humanoid.yaml"}) {
    const Scene scene = load(file);
    for (const Traversal t : kTraversals)
      expect_non_finite_rows_collide(checker_for(scene, "gpu", t).get(), scene,
                                     std::string("gpu ") + traversal_name(t) + " " + file);
  }
}

// The local planner refuses a motion to a non-finite row instead of sampling it.
TEST(StabilityHostileInput, MotionsToNonFiniteRowsAreRefused) {
  const Scene scene = load("piano.yaml");
  auto checker = checker_for(scene, "cpu");
  LocalPlanner local(scene, checker.get());
  std::vector<float> a = sample(scene, 1, 3), b = a;
  b[0] = std::numeric_limits<float>::infinity();
  std::uint8_t invalid = 0;
  EXPECT_THROW(local.check_motions(a.data(), b.data(), 1, &invalid), std::invalid_argument);
}

// --- quaternions far from unit length ------------------------------------------------------

void expect_quaternion_scales(CollisionChecker* checker, const Scene& scene) {
  const std::size_t n = 2000, w = 7;
  const std::vector<float> q = sample(scene, n, 11);
  FclChecker fcl(scene);
  const std::vector<std::uint8_t> truth = verdicts(&fcl, q, w);
  for (const float scale : {1e-30f, 1e-20f, 1e-12f, 1e12f, 1e20f, 1e30f}) {
    std::vector<float> scaled = q;
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 3; k < 7; ++k) scaled[i * w + k] *= scale;
    const std::vector<std::uint8_t> got = verdicts(checker, scaled, w);
    const CheckerComparison c =
        compare_verdicts(q.data(), n, w, got.data(), truth.data(), &fcl, tolerance_delta(scene));
    EXPECT_EQ(c.missed_collisions, 0u) << checker->backend() << ", quaternions scaled by " << scale;
    EXPECT_EQ(c.extra_outside_band, 0u)
        << checker->backend() << ", quaternions scaled by " << scale;
  }
}

TEST(StabilityHostileInput, QuaternionsOfAnyFiniteLengthCpuAndFcl) {
  const Scene scene = load("piano.yaml");
  expect_quaternion_scales(checker_for(scene, "cpu").get(), scene);
  expect_quaternion_scales(checker_for(scene, "fcl").get(), scene);
}

TEST(StabilityHostileInput, GpuQuaternionsOfAnyFiniteLength) {
  REQUIRE_GPU();
  const Scene scene = load("piano.yaml");
  for (const Traversal t : kTraversals)
    expect_quaternion_scales(checker_for(scene, "gpu", t).get(), scene);
}

// --- a link of one nanometre ----------------------------------------------------------------

// A 1 nm cube on a prismatic joint along x, in front of a plate whose face is x = 0.5.
const char* const kSpeckUrdf = R"(<robot name="speck">
  <link name="base"><collision><origin xyz="0 0 -1"/><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="speck"><collision><geometry><box size="1e-9 1e-9 1e-9"/></geometry></collision></link>
  <joint name="slide" type="prismatic"><parent link="base"/><child link="speck"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
</robot>
)";

void expect_speck_checked(const std::vector<std::string>& backends) {
  testing::ScratchFolder scratch;
  scratch.write("speck.urdf", kSpeckUrdf);
  const Scene scene = load_scene(scratch.write(
      "scene.yaml",
      "name: speck\nrobot:\n  urdf: speck.urdf\n  planned_joints: [slide]\nobstacles:\n"
      "  - box: [0.2, 1, 1]\n    pose: {xyz: [0.6, 0, 0]}\nstart:\n  joints: {slide: 0}\n"
      "goal:\n  joints: {slide: 0.2}\n"));
  const double delta = tolerance_delta(scene);
  ASSERT_GT(1e-3, 10 * delta);
  struct Case {
    float slide;
    bool collides;
  };
  // The speck's centre at `slide`: straddling the face at 0.5, or clear of it by
  // 1 mm and more.
  const Case cases[] = {{0.5f, true}, {0.499f, false}, {0.2f, false}};
  for (const std::string& backend : backends) {
    auto checker = checker_for(scene, backend);
    for (const Case& c : cases) {
      EXPECT_EQ(checker->in_collision(&c.slide), c.collides) << backend << ", slide " << c.slide;
    }
  }
}

TEST(StabilityHostileInput, NanometreLinkCpuAndFcl) { expect_speck_checked({"cpu", "fcl"}); }

TEST(StabilityHostileInput, GpuNanometreLink) {
  REQUIRE_GPU();
  expect_speck_checked({"gpu"});
}

// --- links of zero size -------------------------------------------------------------------

// A zero-size box or a zero mesh scale is refused at load, naming the URDF file, the
// line of the element and what is wrong; an obstacle mesh scaled by zero likewise.
TEST(StabilityHostileInput, ZeroSizeLinksAreRefusedWithTheirLine) {
  testing::ScratchFolder scratch;
  scratch.write("tetra.obj",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const std::string scene = scratch.write(
      "scene.yaml",
      "name: zero\nrobot:\n  urdf: zero.urdf\n  planned_joints: [slide]\nobstacles:\n"
      "  - box: [0.2, 1, 1]\n    pose: {xyz: [0.6, 0, 0]}\nstart:\n  joints: {slide: 0}\n"
      "goal:\n  joints: {slide: 0.2}\n");
  for (const std::string& geometry :
       {std::string("<box size=\"0 0.1 0.1\"/>"), std::string("<box size=\"0 0 0\"/>"),
        std::string("<mesh filename=\"tetra.obj\" scale=\"1 0 1\"/>"),
        std::string("<mesh filename=\"tetra.obj\" scale=\"0 0 0\"/>")}) {
    const std::string speck = "<box size=\"1e-9 1e-9 1e-9\"/>";
    std::string urdf = kSpeckUrdf;
    urdf.replace(urdf.find(speck), speck.size(), geometry);
    const std::string urdf_path = scratch.write("zero.urdf", urdf);
    try {
      load_scene(scene);
      ADD_FAILURE() << geometry << ": loaded";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(e.where().file, urdf_path) << message;
      EXPECT_EQ(e.where().line, 3) << message;  // the speck's <box> or <mesh>
      const bool says_what =
          message.find("is not three positive finite numbers") != std::string::npos ||
          message.find("is not three finite non-zero numbers") != std::string::npos;
      EXPECT_TRUE(says_what) << message;
    }
  }
  const std::string flat =
      scratch.write("flat.yaml",
                    "name: zero\nrobot:\n  mesh: tetra.obj\nobstacles:\n  - mesh: tetra.obj\n    "
                    "scale: [1, 0, 1]\n"
                    "bounds:\n  min: [-2, -2, -2]\n  max: [2, 2, 2]\n"
                    "start:\n  base: {xyz: [-1, -1, -1], quat_wxyz: [1, 0, 0, 0]}\n"
                    "goal:\n  base: {xyz: [1, 1, 1], quat_wxyz: [1, 0, 0, 0]}\n");
  try {
    load_scene(flat);
    ADD_FAILURE() << "an obstacle scaled by zero loaded";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 6) << e.what();
    EXPECT_NE(std::string(e.what()).find("zero scale"), std::string::npos) << e.what();
  }
}

// --- two million triangles -------------------------------------------------------------

// A binary STL of a flat grid over [-1, 1]^2 at z = 0: cells x cells squares, two
// triangles each.
void write_grid_stl(const std::string& path, int cells) {
  std::ofstream out(path, std::ios::binary);
  const char header[80] = "gplanner stability: flat grid";
  out.write(header, 80);
  const std::uint32_t count = 2u * cells * cells;
  out.write(reinterpret_cast<const char*>(&count), 4);
  std::vector<char> buffer;
  buffer.reserve(static_cast<std::size_t>(cells) * 2 * 50);
  auto put = [&](float v) {
    const char* p = reinterpret_cast<const char*>(&v);
    buffer.insert(buffer.end(), p, p + 4);
  };
  const double step = 2.0 / cells;
  for (int i = 0; i < cells; ++i) {
    buffer.clear();
    const float x0 = float(-1 + i * step), x1 = float(-1 + (i + 1) * step);
    for (int j = 0; j < cells; ++j) {
      const float y0 = float(-1 + j * step), y1 = float(-1 + (j + 1) * step);
      const float tri[2][9] = {{x0, y0, 0, x1, y0, 0, x1, y1, 0},
                               {x0, y0, 0, x1, y1, 0, x0, y1, 0}};
      for (const auto& t : tri) {
        put(0);
        put(0);
        put(1);
        for (const float v : t) put(v);
        buffer.push_back(0);
        buffer.push_back(0);
      }
    }
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
  }
}

long peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A 0.1 m cube over the grid, turned at random: its distance to the plane is its
// lowest corner's height, known from the float configuration.
void expect_big_grid_checked(const std::vector<std::string>& backends) {
  constexpr int kCells = 1000;  // 2,000,000 triangles
  testing::ScratchFolder scratch;
  write_grid_stl(scratch.path() + "/grid.stl", kCells);
  scratch.write("cube.obj",
                "v -0.05 -0.05 -0.05\nv 0.05 -0.05 -0.05\nv 0.05 0.05 -0.05\nv -0.05 0.05 -0.05\n"
                "v -0.05 -0.05 0.05\nv 0.05 -0.05 0.05\nv 0.05 0.05 0.05\nv -0.05 0.05 0.05\n"
                "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n");
  const auto start = std::chrono::steady_clock::now();
  const Scene scene = load_scene(
      scratch.write("scene.yaml",
                    "name: grid\nrobot:\n  mesh: cube.obj\nobstacles:\n  - mesh: grid.stl\n"
                    "bounds:\n  min: [-1, -1, -1]\n  max: [1, 1, 1]\n"
                    "start:\n  base: {xyz: [0, 0, 0.5], quat_wxyz: [1, 0, 0, 0]}\n"
                    "goal:\n  base: {xyz: [0.5, 0, 0.5], quat_wxyz: [1, 0, 0, 0]}\n"));
  const double load_s = seconds_since(start);
  ASSERT_EQ(scene.obstacle_triangle_count(), 2u * kCells * kCells);
  const double delta = tolerance_delta(scene);
  // Heights of the lowest corner: through the plane, touching it, within the band,
  // beyond it.
  const double heights[] = {-1e-2, -1e-4, 0, 0.25 * delta, 2 * delta, 1e-3, 0.1};
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> xy(-0.8, 0.8);
  std::vector<float> q;
  std::vector<double> distance;
  std::vector<bool> through;  // the cube's lowest corner 0.1 mm or more below the plane
  for (int i = 0; i < 700; ++i) {
    float row[7];
    const Eigen::Quaterniond r = Eigen::Quaterniond::UnitRandom();
    row[0] = float(xy(rng));
    row[1] = float(xy(rng));
    row[2] = 0;
    row[3] = float(r.w());
    row[4] = float(r.x());
    row[5] = float(r.y());
    row[6] = float(r.z());
    double lowest = 1e9;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner((c & 1) ? 0.05 : -0.05, (c & 2) ? 0.05 : -0.05,
                                   (c & 4) ? 0.05 : -0.05);
      lowest = std::min(lowest, (scene.space.base_pose(row) * corner).z());
    }
    row[2] = float(heights[i % 7] - lowest);
    const double realised = lowest + double(row[2]);
    q.insert(q.end(), row, row + 7);
    distance.push_back(std::max(0.0, realised));
    through.push_back(realised < -5e-5);
  }
  const std::size_t n = distance.size();
  for (const std::string& backend : backends) {
    const auto build_start = std::chrono::steady_clock::now();
    auto checker = checker_for(scene, backend);
    const double build_s = seconds_since(build_start);
    const auto check_start = std::chrono::steady_clock::now();
    const std::vector<std::uint8_t> got = verdicts(checker.get(), q, 7);
    const double check_s = seconds_since(check_start);
    std::size_t fcl_touching_free = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::string what = backend + ", lowest corner at " + std::to_string(distance[i]);
      if (distance[i] > delta) EXPECT_EQ(got[i], 0) << what << ": outside the band";
      if (through[i]) EXPECT_EQ(got[i], 1) << what << ": through the plane, reported free";
      if (distance[i] == 0 && backend != "fcl") EXPECT_EQ(got[i], 1) << what << ": contact missed";
      if (distance[i] == 0 && backend == "fcl") fcl_touching_free += got[i] == 0;
    }
    std::cout << "2,000,000 triangles, " << backend << ": scene loaded in " << load_s
              << " s, checker built in " << build_s << " s, " << n << " queries in " << check_s
              << " s; peak memory " << peak_rss_mb() << " MB";
    if (backend == "fcl") std::cout << "; fcl free at contact: " << fcl_touching_free;
    std::cout << "\n";
    // Bounded: far under a minute each on one core, and a few GB at most.
    EXPECT_LT(build_s, 120.0) << backend;
    EXPECT_LT(check_s, 60.0) << backend;
  }
  EXPECT_LT(load_s, 120.0);
  EXPECT_LT(peak_rss_mb(), 6000);
}

TEST(StabilityHostileInput, TwoMillionTriangleObstacleCpuAndFcl) {
  expect_big_grid_checked({"cpu", "fcl"});
}

TEST(StabilityHostileInput, GpuTwoMillionTriangleObstacle) {
  REQUIRE_GPU();
  expect_big_grid_checked({"gpu"});
}

// --- over the memory cap ---------------------------------------------------------------------

TEST(StabilityHostileInput, GpuBatchesOverATinyMemoryCapAnswerAsTheCpu) {
  REQUIRE_GPU();
  for (const char* file : {"piano.yaml", "humanoid.yaml"}) {
    const Scene scene = load(file);
    // 50,000 rows of 7 floats (piano) or more are over 1 MiB in themselves.
    const std::size_t n = 50000, w = scene.space.width();
    const std::vector<float> q = sample(scene, n, 13);
    auto cpu = checker_for(scene, "cpu");
    const std::vector<std::uint8_t> expected = verdicts(cpu.get(), q, w);
    FclChecker fcl(scene);
    for (const Traversal t : kTraversals) {
      GpuCheckerOptions options;
      options.traversal = t;
      options.memory_cap_bytes = std::size_t(1) << 20;  // gplan check --memory-cap-mb 1
      options.host_calls_up_to = 0;
      GpuChecker gpu(scene, options);
      std::vector<std::uint8_t> got(n, 2);
      gpu.check(q.data(), n, got.data());
      EXPECT_GT(gpu.last_stats().chunks, 1u) << file << " " << traversal_name(t);
      const CheckerComparison c = compare_verdicts(q.data(), n, w, got.data(), expected.data(),
                                                   &fcl, tolerance_delta(scene));
      EXPECT_EQ(c.missed_collisions, 0u) << file << " " << traversal_name(t);
      EXPECT_EQ(c.extra_outside_band, 0u) << file << " " << traversal_name(t);
      EXPECT_LE(c.disagreements, n / 200) << file << " " << traversal_name(t);
    }
  }
}

}  // namespace
}  // namespace gplanner
