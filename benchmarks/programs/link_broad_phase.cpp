// The planner's own broad phase at the sizes of issue 23 (a measurement, nothing in the
// checker changes): a robot of L link spheres with P checked link pairs (a humanoid: 50
// links, 1,000 pairs) among B obstacle spheres (the bounding spheres of B separate boxes),
// per configuration, on one CPU thread:
//   link-pairs  the P masked pair tests (what the checker's broad phase does today)
//   link-sweep  sort-and-sweep over the L link spheres, then the mask (same pairs)
//   obst-all    every link against every obstacle: L x B tests (separate bodies, no BVH)
//   obst-sweep  the obstacles' x-intervals sorted once (static); each link sphere's
//               candidates found by two binary searches (same pairs as obst-all)
// and, where a GPU can be used, one configuration's L + B spheres through the GPU broad
// phase (gpu-sort-sweep, gpu-grid, gpu-lbvh: a call per configuration, transfers
// included; its pairs include the static obstacle pairs). Prints one JSON line per B with
// the nanoseconds per configuration (GPU: per call), and exits 1 when two methods that
// must agree do not.
//
// usage: gplanner_link_broad_phase [--links L] [--pairs P] [--configurations C] [--seed S]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "gplanner/collision_gpu/broad_phase.h"
#include "gplanner/collision_gpu/geometry/sphere_overlap.h"
#include "gplanner/collision_gpu/gpu_broad_phase.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Sphere {
  float x, y, z, r;
};

bool overlap(const Sphere& a, const Sphere& b) {
  return gplanner::geometry::spheres_overlap(a.x, a.y, a.z, a.r, b.x, b.y, b.z, b.r);
}

// One configuration's link spheres: within a 1 x 1 x 2 m body at a base placed in the room.
std::vector<Sphere> robot(std::mt19937_64& rng, int links, float room) {
  std::uniform_real_distribution<float> base(1.f, room - 1.f), u(0.f, 1.f), r(0.05f, 0.15f);
  const float bx = base(rng), by = base(rng);
  std::vector<Sphere> s(links);
  for (Sphere& x : s) x = {bx + u(rng) - 0.5f, by + u(rng) - 0.5f, 2.f * u(rng), r(rng)};
  return s;
}

double ns_since(Clock::time_point start, long long per) {
  return std::chrono::duration<double, std::nano>(Clock::now() - start).count() / double(per);
}

}  // namespace

int main(int argc, char** argv) {
  int links = 50, checked = 1000, configurations = 20000;
  unsigned long long seed = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const long long value = std::atoll(argv[i + 1]);
    if (key == "--links")
      links = int(value);
    else if (key == "--pairs")
      checked = int(value);
    else if (key == "--configurations")
      configurations = int(value);
    else if (key == "--seed")
      seed = static_cast<unsigned long long>(value);
    else {
      std::fprintf(stderr, "usage: %s [--links L] [--pairs P] [--configurations C] [--seed S]\n",
                   argv[0]);
      return 2;
    }
  }
  if (links < 2 || checked < 1 || checked > links * (links - 1) / 2 || configurations < 1) {
    std::fprintf(stderr, "need 2 <= L, 1 <= P <= L(L-1)/2, 1 <= C\n");
    return 2;
  }
  std::mt19937_64 rng(seed);
  // The checked pairs: P of the L(L-1)/2, seeded; and the same as a mask.
  std::vector<std::pair<int, int>> all;
  for (int a = 0; a < links; ++a)
    for (int b = a + 1; b < links; ++b) all.push_back({a, b});
  std::shuffle(all.begin(), all.end(), rng);
  all.resize(checked);
  std::sort(all.begin(), all.end());
  std::vector<unsigned char> mask(std::size_t(links) * links, 0);
  for (const auto& [a, b] : all) mask[std::size_t(a) * links + b] = 1;

  std::string gpu_reason;
  const bool gpu_here = gplanner::gpu_broad_phase_available(&gpu_reason);
  int status = 0;
  for (const int boxes : {1000, 3000, 10000}) {
    const float room = 10.f;
    std::uniform_real_distribution<float> u(0.f, room), uz(0.f, 3.f), r(0.05f, 0.3f);
    std::vector<Sphere> obstacles(boxes);
    for (Sphere& o : obstacles) o = {u(rng), u(rng), uz(rng), r(rng)};
    std::vector<std::vector<Sphere>> robots;
    for (int c = 0; c < configurations; ++c) robots.push_back(robot(rng, links, room));

    // Link pairs: the mask's pairs, then sort-and-sweep.
    long long masked_hits = 0, swept_hits = 0, all_hits = 0, sweep_obstacle_hits = 0;
    auto start = Clock::now();
    for (const auto& s : robots)
      for (const auto& [a, b] : all) masked_hits += overlap(s[a], s[b]);
    const double link_pairs_ns = ns_since(start, configurations);
    std::vector<int> order(links);
    start = Clock::now();
    for (const auto& s : robots) {
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(), [&](int a, int b) {
        return gplanner::geometry::cull_low(s[a].x, s[a].r) <
               gplanner::geometry::cull_low(s[b].x, s[b].r);
      });
      for (int k = 0; k < links; ++k) {
        const Sphere& a = s[order[k]];
        const float end = gplanner::geometry::cull_high(a.x, a.r);
        for (int m = k + 1; m < links; ++m) {
          const Sphere& b = s[order[m]];
          if (gplanner::geometry::cull_low(b.x, b.r) > end) break;
          const int i = std::min(order[k], order[m]), j = std::max(order[k], order[m]);
          if (mask[std::size_t(i) * links + j] && overlap(a, b)) ++swept_hits;
        }
      }
    }
    const double link_sweep_ns = ns_since(start, configurations);

    // Links against obstacles: all of them, then the static sorted intervals.
    const int obstacle_configurations = std::max(1, configurations / 10);
    start = Clock::now();
    for (int c = 0; c < obstacle_configurations; ++c)
      for (const Sphere& l : robots[c])
        for (const Sphere& o : obstacles) all_hits += overlap(l, o);
    const double obstacles_all_ns = ns_since(start, obstacle_configurations);
    std::vector<Sphere> sorted = obstacles;
    std::sort(sorted.begin(), sorted.end(), [](const Sphere& a, const Sphere& b) {
      return gplanner::geometry::cull_low(a.x, a.r) < gplanner::geometry::cull_low(b.x, b.r);
    });
    std::vector<float> low(boxes);
    float widest = 0;
    for (int k = 0; k < boxes; ++k) {
      low[k] = gplanner::geometry::cull_low(sorted[k].x, sorted[k].r);
      widest = std::max(widest, gplanner::geometry::cull_high(sorted[k].x, sorted[k].r) - low[k]);
    }
    start = Clock::now();
    for (int c = 0; c < obstacle_configurations; ++c) {
      for (const Sphere& l : robots[c]) {
        const float lo = gplanner::geometry::cull_low(l.x, l.r);
        const float hi = gplanner::geometry::cull_high(l.x, l.r);
        // Obstacles whose interval may meet [lo, hi]: low in [lo - widest, hi].
        const auto first = std::lower_bound(low.begin(), low.end(), lo - widest);
        const auto last = std::upper_bound(first, low.end(), hi);
        for (auto it = first; it != last; ++it)
          sweep_obstacle_hits += overlap(l, sorted[std::size_t(it - low.begin())]);
      }
    }
    const double obstacles_sweep_ns = ns_since(start, obstacle_configurations);
    if (masked_hits != swept_hits || all_hits != sweep_obstacle_hits) {
      std::fprintf(stderr, "MISMATCH at %d boxes: link pairs %lld / %lld, obstacles %lld / %lld\n",
                   boxes, masked_hits, swept_hits, all_hits, sweep_obstacle_hits);
      status = 1;
    }

    // One configuration's L + B spheres through the GPU broad phase, a call each.
    std::string gpu_json;
    if (gpu_here) {
      gplanner::GpuBroadPhase gpu;
      std::vector<float> centers, radii;
      for (const std::vector<Sphere>* part : {&robots[0], &obstacles})
        for (const Sphere& s : *part) {
          centers.insert(centers.end(), {s.x, s.y, s.z});
          radii.push_back(s.r);
        }
      const gplanner::SphereArrays spheres{centers.data(), radii.data(), radii.size()};
      std::vector<gplanner::SpherePair> pairs;
      for (const auto method :
           {gplanner::BroadPhaseMethod::kGpuSortSweep, gplanner::BroadPhaseMethod::kGpuGrid,
            gplanner::BroadPhaseMethod::kGpuLbvh}) {
        gpu.find_pairs(method, spheres, &pairs);  // warm-up
        std::vector<double> ns;
        for (int k = 0; k < 50; ++k) {
          const auto t = Clock::now();
          gpu.find_pairs(method, spheres, &pairs);
          ns.push_back(ns_since(t, 1));
        }
        std::sort(ns.begin(), ns.end());
        gpu_json += ",\"" + std::string(gplanner::broad_phase_method_name(method)) +
                    "_ns_per_call\":" + std::to_string(ns[ns.size() / 2]);
      }
      gpu_json += ",\"gpu\":\"" + gpu.device_name() + "\"";
    } else {
      gpu_json = ",\"gpu\":null,\"no_gpu\":\"" + gpu_reason + "\"";
    }
    std::printf(
        "{\"links\":%d,\"checked_pairs\":%d,\"boxes\":%d,\"configurations\":%d,"
        "\"link_pairs_ns\":%.1f,\"link_sweep_ns\":%.1f,\"obstacles_all_ns\":%.1f,"
        "\"obstacles_sweep_ns\":%.1f,\"link_hits_per_configuration\":%.3f,"
        "\"obstacle_hits_per_configuration\":%.3f%s}\n",
        links, checked, boxes, configurations, link_pairs_ns, link_sweep_ns, obstacles_all_ns,
        obstacles_sweep_ns, double(masked_hits) / configurations,
        double(all_hits) / obstacle_configurations, gpu_json.c_str());
    std::fflush(stdout);
  }
  return status;
}
