// GPU tests (names contain "Gpu"): the gpu backend, each traversal, against the cpu
// backend on seeded batches of every shipped scene. They assert that the GPU ran and
// skip only where there is no device.

#include "gplanner/planner/checkers/gpu_checker.h"

#include <gtest/gtest.h>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/checker_comparison.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "planner/scene_test_support.h"
#include "require_gpu.h"
#include "test_support.h"

namespace gplanner {
namespace {

struct Case {
  std::string scene;
  Traversal traversal;
  bool small_batch = false;  // balanced: the whole batch a warp per body pair, no rounds
};

std::string case_name(const Case& c) {
  return std::string(traversal_name(c.traversal)) + (c.small_batch ? "_small_batch" : "");
}

void PrintTo(const Case& c, std::ostream* out) { *out << c.scene << " " << case_name(c); }

// The kernels under test: no call answered on the host.
GpuCheckerOptions gpu_only() {
  GpuCheckerOptions options;
  options.host_calls_up_to = 0;
  return options;
}
const GpuCheckerOptions kGpuOnly = gpu_only();

class GpuMatchesCpu : public ::testing::TestWithParam<Case> {};

TEST_P(GpuMatchesCpu, OnASeededBatch) {
  REQUIRE_GPU();
  const Scene scene = load_scene(testing::project_root() + "/scenes/" + GetParam().scene);
  const std::size_t n = 5000, width = scene.space.width();
  const std::vector<float> q = testing::sample_configurations(scene, n, 23);
  CheckerOptions options;
  options.gpu.traversal = GetParam().traversal;
  options.gpu.warp_per_pair_up_to = GetParam().small_batch ? n : 0;
  options.gpu.host_calls_up_to = 0;  // the kernels under test
  std::string notice;
  const std::unique_ptr<CollisionChecker> checker =
      make_collision_checker(scene, "gpu", options, &notice);
  ASSERT_EQ(checker->backend(), "gpu") << notice;
  auto* gpu = dynamic_cast<GpuChecker*>(checker.get());
  ASSERT_NE(gpu, nullptr);
  std::vector<std::uint8_t> on_gpu(n), on_cpu(n);
  gpu->check(q.data(), n, on_gpu.data());
  EXPECT_GT(gpu->last_stats().bv_tests, 0u) << "the GPU did no work";
  EXPECT_GT(gpu->last_stats().milliseconds, 0.0);
  EXPECT_EQ(gpu->last_stats().warp_per_pair, GetParam().small_batch);
  CpuChecker cpu(scene);
  cpu.check(q.data(), n, on_cpu.data());
  FclChecker fcl(scene);
  const CheckerComparison c = compare_verdicts(q.data(), n, width, on_gpu.data(), on_cpu.data(),
                                               &fcl, tolerance_delta(scene));
  EXPECT_EQ(c.missed_collisions, 0u);
  EXPECT_EQ(c.extra_outside_band, 0u);
  EXPECT_LE(c.disagreements, n / 200)
      << "GPU and CPU run the same code: they should nearly always agree";
  std::cout << GetParam().scene << " " << case_name(GetParam()) << ": " << c.disagreements
            << " disagreements with the cpu backend, " << gpu->last_stats().milliseconds << " ms, "
            << gpu->last_stats().bv_tests << " BV tests, " << gpu->last_stats().triangle_tests
            << " triangle tests on " << gpu->device_name() << "\n";
}

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (const std::string& scene : testing::shipped_scene_files()) {
    for (const Traversal t : {Traversal::kBasic, Traversal::kPacket, Traversal::kBalanced})
      cases.push_back({scene, t});
    cases.push_back({scene, Traversal::kBalanced, true});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Scenes, GpuMatchesCpu, ::testing::ValuesIn(all_cases()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           return testing::scene_test_name(info.param.scene) + "_" +
                                  case_name(info.param);
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(GpuMatchesCpu);

// The parameterised GPU cases above exist only if the scenes are found: run from the
// project root or set GPLANNER_ROOT.
TEST(GpuChecker, FindsTheShippedScenes) {
  EXPECT_GE(testing::shipped_scene_files().size(), 7u)
      << "scenes/ not found under " << testing::project_root();
}

TEST(GpuChecker, ChunksBatchesOverTheMemoryCap) {
  REQUIRE_GPU();
  const Scene scene = load_scene(testing::project_root() + "/scenes/humanoid.yaml");
  const std::size_t n = 3000;
  const std::vector<float> q = testing::sample_configurations(scene, n, 29);
  for (const Case c : {Case{"", Traversal::kBasic}, Case{"", Traversal::kPacket},
                       Case{"", Traversal::kBalanced}, Case{"", Traversal::kBalanced, true}}) {
    GpuCheckerOptions whole, capped;
    whole.traversal = capped.traversal = c.traversal;
    whole.warp_per_pair_up_to = capped.warp_per_pair_up_to = c.small_batch ? n : 0;
    capped.memory_cap_bytes = 256 * 1024;
    whole.host_calls_up_to = capped.host_calls_up_to = 0;
    GpuChecker a(scene, whole), b(scene, capped);
    std::vector<std::uint8_t> va(n), vb(n);
    a.check(q.data(), n, va.data());
    b.check(q.data(), n, vb.data());
    EXPECT_EQ(a.last_stats().chunks, 1u) << case_name(c);
    EXPECT_GT(b.last_stats().chunks, 1u) << case_name(c);
    EXPECT_EQ(va, vb) << case_name(c);
  }
}

// The balanced traversal's kinematics and broad phase run a warp per query for an arm
// with hundreds of sphere tests in batches of up to 16,384 queries, a thread per query
// for larger batches and for a rigid body; small batches run a warp per body pair in one
// kernel (by default up to 1,024 queries of a PR2 arm, 4,096 of an arm of few bodies,
// 10 of a rigid body), larger ones in
// rounds of tasks, whose short remainder a warp per task finishes. The verdicts of every
// kind are compared with the cpu backend above; this asserts which kind ran.
TEST(GpuChecker, ChoosesItsKernelsByRobotAndBatchSize) {
  REQUIRE_GPU();
  struct Expect {
    std::string scene;
    std::size_t n;
    int root_lanes;
    bool warp_per_pair;
  };
  for (const Expect& e :
       {Expect{"pr2_base_arm.yaml", 64, 32, true}, Expect{"pr2_base_arm.yaml", 2000, 32, false},
        Expect{"pr2_base_arm.yaml", 20000, 1, false}, Expect{"piano.yaml", 8, 1, true},
        Expect{"piano.yaml", 32, 1, false}}) {
    const Scene scene = load_scene(testing::project_root() + "/scenes/" + e.scene);
    const std::vector<float> q = testing::sample_configurations(scene, e.n, 31);
    GpuChecker gpu(scene, kGpuOnly);
    std::vector<std::uint8_t> verdicts(e.n);
    gpu.check(q.data(), e.n, verdicts.data());
    EXPECT_EQ(gpu.last_stats().root_lanes, e.root_lanes) << e.scene << " " << e.n;
    EXPECT_EQ(gpu.last_stats().warp_per_pair, e.warp_per_pair) << e.scene << " " << e.n;
    // 20,000 queries of an arm leave tens of thousands of tasks after two rounds; the
    // queue shrinks round by round until the finish kernel takes the last few thousand.
    if (e.n == 20000) EXPECT_GT(gpu.last_stats().finished_tasks, 0u) << e.scene;
  }
  // An arm of few bodies (the Panda: 34 links and pairs) runs batches of up to 4,096 a
  // warp per body pair, one kernel.
  const std::string data = testing::shared_data();
  if (data.empty()) GTEST_SKIP() << "no ../shared/data (set GPLANNER_SHARED_DATA)";
  const std::string panda = data + "/motionbenchmaker/panda";
  const testing::ScratchFolder folder;
  const Scene scene = load_scene(folder.write(
      "box.yaml", "name: box_0001\nrobot:\n  urdf: " + panda + "/robot/panda.urdf\n  srdf: " +
                      panda + "/robot/panda.srdf\n  packages: {meshes: " + panda +
                      "/robot/meshes}\nmoveit:\n  scene: " + panda +
                      "/problems/box_panda/scene0001.yaml\n  request: " + panda +
                      "/problems/box_panda/request0001.yaml\n"));
  GpuChecker gpu(scene, kGpuOnly);
  for (const std::size_t n : {std::size_t(4096), std::size_t(4097)}) {
    const std::vector<float> q = testing::sample_configurations(scene, n, 31);
    std::vector<std::uint8_t> verdicts(n);
    gpu.check(q.data(), n, verdicts.data());
    EXPECT_EQ(gpu.last_stats().warp_per_pair, n <= 4096) << "Panda " << n;
  }
}

// Calls of every size: the gpu backend as made by default answers small calls on the
// host, by crossovers it measured on the scene, and every size agrees with the same core
// on the host (the cpu backend, exactly, where the host answered) and with FCL up to the
// band; the GPU's small batches (one wait, page-locked staging) agree too.
TEST(GpuChecker, RoutesCallsOfEverySizeByMeasuredCrossovers) {
  REQUIRE_GPU();
  for (const char* name : {"piano.yaml", "pr2_base_arm.yaml"}) {
    const Scene scene = load_scene(testing::project_root() + "/scenes/" + name);
    GpuChecker routed(scene, GpuCheckerOptions{});
    GpuChecker gpu_only(scene, kGpuOnly);
    const HostCallRouting& r = routed.routing();
    ASSERT_TRUE(r.measured) << name;
    ASSERT_EQ(r.sizes.size(), r.gpu_seconds.size()) << name;
    EXPECT_GT(r.host_seconds_per_configuration, 0.0) << name;
    for (const double t : r.gpu_seconds) EXPECT_GT(t, 0.0) << name;
    EXPECT_LE(r.calling_thread_up_to, r.host_threads_up_to) << name;
    ASSERT_EQ(r.sizes.size(), r.calling_thread_seconds.size()) << name;
    // The calling thread where it beat the pool, as measured.
    for (std::size_t i = 0; i < r.sizes.size() && r.sizes[i] <= r.calling_thread_up_to; ++i)
      EXPECT_LE(r.calling_thread_seconds[i], r.host_threads_seconds[i]) << name << " " << r.sizes[i];
    // The first decision as the measurements say: one state on the host when that beat a
    // GPU call of one state.
    EXPECT_EQ(r.host_threads_up_to > 0,
              std::min(r.calling_thread_seconds.front(), r.host_threads_seconds.front()) <=
                  r.gpu_seconds.front())
        << name;
    std::cout << name << ": calling thread up to " << r.calling_thread_up_to
              << ", host threads up to " << r.host_threads_up_to << "; one state "
              << r.host_seconds_per_configuration * 1e6 << " us on the host, "
              << r.gpu_seconds.front() * 1e6 << " us on the GPU\n";
    const std::size_t most = 4096, width = scene.space.width();
    const std::vector<float> q = testing::sample_configurations(scene, most, 37);
    CpuChecker cpu(scene);
    FclChecker fcl(scene);
    std::vector<std::uint8_t> on_cpu(most);
    cpu.check(q.data(), most, on_cpu.data());
    for (std::size_t n = 1; n <= most; n *= 2) {
      std::vector<std::uint8_t> a(n), b(n);
      const std::size_t on_host_up_to = routed.host_calls_up_to();
      EXPECT_LE(on_host_up_to, r.host_threads_up_to) << name;
      routed.check(q.data(), n, a.data());
      gpu_only.check(q.data(), n, b.data());
      EXPECT_GT(gpu_only.last_stats().milliseconds, 0.0) << name << " " << n;
      const std::vector<std::uint8_t> cpu_part(on_cpu.begin(), on_cpu.begin() + n);
      if (n <= on_host_up_to) EXPECT_EQ(a, cpu_part) << name << " " << n;
      for (const std::vector<std::uint8_t>* v : {&a, &b}) {
        const CheckerComparison c = compare_verdicts(q.data(), n, width, v->data(), cpu_part.data(),
                                                     &fcl, tolerance_delta(scene));
        EXPECT_EQ(c.missed_collisions, 0u) << name << " " << n;
        EXPECT_EQ(c.extra_outside_band, 0u) << name << " " << n;
      }
    }
  }
}

TEST(GpuChecker, MeasuresItsCallCostAndLearnsWhatHostCallsCost) {
  REQUIRE_GPU();
  int learnt = 0;
  for (const char* name : {"piano.yaml", "pr2_base_arm.yaml"}) {
    const Scene scene = load_scene(testing::project_root() + "/scenes/" + name);
    // Where the routing is set, not measured: the constant call cost, no learning.
    GpuChecker fixed(scene, kGpuOnly);
    EXPECT_EQ(fixed.configurations_per_call_cost(), 8192u) << name;
    EXPECT_EQ(fixed.host_calls_up_to(), 0u) << name;
    fixed.check(scene.start.data(), 1, std::vector<std::uint8_t>(1).data());
    EXPECT_EQ(fixed.host_cost_ratio(), 1.0) << name;
    // Measured: the cost within its bounds, the ratio from 1.
    GpuChecker routed(scene, GpuCheckerOptions{});
    const HostCallRouting& r = routed.routing();
    EXPECT_EQ(routed.configurations_per_call_cost(), r.call_cost) << name;
    EXPECT_GE(r.call_cost, 256u) << name;
    EXPECT_LE(r.call_cost, 65536u) << name;
    EXPECT_EQ(routed.host_cost_ratio(), 1.0) << name;
    if (r.host_threads_up_to == 0) continue;
    // Single states stay on the host, whatever they cost, and teach the ratio.
    const std::size_t calls_before = routed.device_calls();
    std::uint8_t verdict = 0;
    for (int k = 0; k < 20; ++k) routed.check(scene.start.data(), 1, &verdict);
    EXPECT_EQ(verdict, 0) << name;
    EXPECT_EQ(routed.device_calls(), calls_before) << name;
    const double ratio = routed.host_cost_ratio();
    EXPECT_NE(ratio, 1.0) << name;
    EXPECT_GE(ratio, 0.25) << name;
    EXPECT_LE(ratio, 1000.0) << name;
    EXPECT_GE(routed.host_calls_up_to(), 1u) << name;
    EXPECT_LE(routed.host_calls_up_to(), r.host_threads_up_to) << name;
    EXPECT_EQ(routed.cheap_calls_up_to(), routed.host_calls_up_to()) << name;
    ++learnt;
  }
  EXPECT_GT(learnt, 0) << "no scene's routing put single states on the host";
}

TEST(GpuChecker, AnswersAnEmptyBatch) {
  REQUIRE_GPU();
  const Scene scene = load_scene(testing::project_root() + "/scenes/helicopter.yaml");
  GpuChecker gpu(scene, kGpuOnly);
  gpu.check(nullptr, 0, nullptr);
  EXPECT_EQ(gpu.last_stats().chunks, 0u);
}

}  // namespace
}  // namespace gplanner
