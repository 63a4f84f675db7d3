#include "gplanner/planner/path_shortcutting.h"

#include <algorithm>
#include <limits>
#include <set>
#include <utility>

#include "gplanner/planner/configuration_space.h"

namespace gplanner {
namespace {
// Rounds stop putting midpoints in once the path has this many waypoints.
constexpr std::size_t kMaxWaypoints = 256;
constexpr std::size_t kNone = ~std::size_t(0);
}  // namespace

double path_length(const ConfigurationMetric& metric, const std::vector<float>& path, int width) {
  double length = 0;
  const std::size_t m = path.size() / width;
  for (std::size_t i = 1; i < m; ++i)
    length += configuration_distance(metric, &path[(i - 1) * width], &path[i * width]);
  return length;
}

double shortcut_path(const ConfigurationSpace& space, LocalPlanner* local, LocalPlanner* fine,
                     int rounds, int candidates, std::mt19937_64* rng, std::vector<float>* path) {
  const int width = space.width();
  const ConfigurationMetric& metric = local->metric();
  for (int round = 0; round < rounds; ++round) {
    const std::size_t m = path->size() / width;
    if (m < 3) break;
    // Shortcuts (i, j), j > i + 1: all of them when few, else `candidates` at random.
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    const std::size_t all = (m - 1) * (m - 2) / 2;
    if (all <= static_cast<std::size_t>(candidates)) {
      for (std::size_t i = 0; i + 2 < m; ++i)
        for (std::size_t j = i + 2; j < m; ++j) pairs.emplace_back(i, j);
    } else {
      std::set<std::pair<std::size_t, std::size_t>> chosen;
      std::uniform_int_distribution<std::size_t> pick(0, m - 1);
      while (chosen.size() < static_cast<std::size_t>(candidates)) {
        std::size_t i = pick(*rng), j = pick(*rng);
        if (i > j) std::swap(i, j);
        if (j >= i + 2) chosen.emplace(i, j);
      }
      pairs.assign(chosen.begin(), chosen.end());
    }
    std::vector<float> from(pairs.size() * width), to(pairs.size() * width);
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      std::copy_n(&(*path)[pairs[p].first * width], width, &from[p * width]);
      std::copy_n(&(*path)[pairs[p].second * width], width, &to[p * width]);
    }
    // Where calls cost more than samples (the GPU), every shortcut is checked at the fine
    // resolution at once when that adds fewer samples than a call costs and fits one
    // call: one call instead of two or more.
    std::size_t coarse_samples = 0, fine_samples = 0;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      coarse_samples += local->segments(&from[p * width], &to[p * width]) - 1;
      fine_samples += fine->segments(&from[p * width], &to[p * width]) - 1;
    }
    const bool fine_at_once = fine_samples <= fine->one_batch_samples() &&
                              fine_samples < coarse_samples + local->configurations_per_call_cost();
    std::vector<std::uint8_t> invalid(pairs.size());
    LocalPlanner* first = fine_at_once ? fine : local;
    if (!first->check_motions(from.data(), to.data(), pairs.size(), invalid.data())) break;
    auto d = [&](std::size_t i, std::size_t j) {
      return static_cast<double>(
          configuration_distance(metric, &(*path)[i * width], &(*path)[j * width]));
    };
    // Shortest way through the waypoints in order, over the path's own segments and the
    // shortcuts valid so far; the shortcuts it takes are checked again at the fine
    // resolution, and those failing drop out, until the way holds only certified ones.
    std::vector<std::uint8_t> certified(pairs.size(), fine_at_once ? 1 : 0);
    std::vector<std::size_t> parent(m, 0), via(m, kNone);
    while (true) {
      std::vector<std::vector<std::size_t>> into(m);  // valid shortcuts ending at j
      for (std::size_t p = 0; p < pairs.size(); ++p)
        if (!invalid[p]) into[pairs[p].second].push_back(p);
      std::vector<double> best(m, std::numeric_limits<double>::infinity());
      best[0] = 0;
      for (std::size_t j = 1; j < m; ++j) {
        best[j] = best[j - 1] + d(j - 1, j);
        parent[j] = j - 1;
        via[j] = kNone;
        for (const std::size_t p : into[j]) {
          const std::size_t i = pairs[p].first;
          const double c = best[i] + d(i, j);
          if (c < best[j]) {
            best[j] = c;
            parent[j] = i;
            via[j] = p;
          }
        }
      }
      std::vector<std::size_t> unchecked;
      for (std::size_t j = m - 1; j > 0; j = parent[j])
        if (via[j] != kNone && !certified[via[j]]) unchecked.push_back(via[j]);
      if (unchecked.empty()) break;
      std::vector<float> a(unchecked.size() * width), b(unchecked.size() * width);
      for (std::size_t u = 0; u < unchecked.size(); ++u) {
        std::copy_n(&from[unchecked[u] * width], width, &a[u * width]);
        std::copy_n(&to[unchecked[u] * width], width, &b[u * width]);
      }
      std::vector<std::uint8_t> fails(unchecked.size());
      fine->check_motions(a.data(), b.data(), unchecked.size(), fails.data());
      for (std::size_t u = 0; u < unchecked.size(); ++u) {
        if (fails[u]) {
          invalid[unchecked[u]] = 1;
        } else {
          certified[unchecked[u]] = 1;
        }
      }
    }
    std::vector<std::size_t> kept;
    for (std::size_t j = m - 1;; j = parent[j]) {
      kept.push_back(j);
      if (j == 0) break;
    }
    std::reverse(kept.begin(), kept.end());
    // The kept waypoints, with a midpoint in every segment for the next round.
    std::vector<float> next;
    const bool refine = round + 1 < rounds && 2 * kept.size() <= kMaxWaypoints;
    std::vector<float> mid(width);
    for (std::size_t k = 0; k < kept.size(); ++k) {
      const float* q = &(*path)[kept[k] * width];
      if (k > 0 && refine) {
        space.interpolate(&(*path)[kept[k - 1] * width], q, 0.5, mid.data());
        next.insert(next.end(), mid.begin(), mid.end());
      }
      next.insert(next.end(), q, q + width);
    }
    const bool shorter = kept.size() < m;
    path->swap(next);
    if (!shorter && !refine) break;
  }
  return path_length(metric, *path, width);
}

}  // namespace gplanner
