#include "gplanner/planner/planning/path_shortcutting.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>

#include "gplanner/planner/scene/configuration_space.h"

namespace gplanner {
namespace {
// Rounds stop putting midpoints in once the path has this many waypoints.
constexpr std::size_t kMaxWaypoints = 256;
constexpr std::size_t kNone = ~std::size_t(0);

// The shortcuts a round proposes on a path, with their segment counts.
struct Proposal {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;  // waypoint indices (i, j)
  std::vector<float> from, to;                             // shape [pairs, width]
  std::vector<int> segments;                               // at the (coarse) resolution of `local`
  std::vector<int> fine_segments;  // at the fine resolution
  // Checked at the fine resolution at once (no second check): where calls cost more
  // than the extra samples and the fine samples fit one call. The coarse samples are
  // then checked too where they are not among the fine ones (coarse_too: those
  // shortcuts), so that a shortcut passes exactly where the two stages, coarse then
  // fine, would pass it: the same paths whatever a call costs.
  bool fine_at_once = false;
  std::vector<std::size_t> coarse_too;
  // Every shortcut of the path (no random choice): a round that leaves the path as it
  // was would propose and find the same again.
  bool all_pairs = false;
  // Shortcuts whose verdicts are known without a check: -1 not known (checked, in order
  // in `checked`), 0 free at the coarse resolution, 1 not free. known_second: free at the
  // second check's too (fine's, or certified). Known: a shortcut that is what the path
  // already is (midpoint_chain), free by the path's own checks; one checked before
  // (ShortcutMemo).
  std::vector<std::int8_t> known;
  std::vector<std::uint8_t> known_second;
  std::vector<std::size_t> checked;
};

// What the rounds have found of shortcuts, by their two ends: a motion checked again
// gives the verdicts it gave, so a shortcut proposed again is not checked again. The
// kept waypoints' pairs come back round after round, and a shortcut that fails its
// second check would be taken by the next round's way, and checked, again.
class ShortcutMemo {
 public:
  struct Verdicts {
    std::int8_t coarse = -1;  // -1 not known, 0 free, 1 not (by either check)
    std::int8_t second = -1;  // the second check's: fine's, or certified
  };
  explicit ShortcutMemo(int width) : width_(width) {}
  const Verdicts* find(const float* from, const float* to) const {
    const auto it = by_ends_.find(key(from, to));
    return it == by_ends_.end() ? nullptr : &it->second;
  }
  Verdicts& at(const float* from, const float* to) { return by_ends_[key(from, to)]; }

 private:
  std::string key(const float* from, const float* to) const {
    std::string k(2 * width_ * sizeof(float), '\0');
    std::memcpy(k.data(), from, width_ * sizeof(float));
    std::memcpy(k.data() + width_ * sizeof(float), to, width_ * sizeof(float));
    return k;
  }
  int width_;
  std::unordered_map<std::string, Verdicts> by_ends_;
};

// Whether the waypoints strictly between i and j are nested midpoints of the motion from
// i to j: j - i a power of two, waypoint (i + j) / 2 exactly the midpoint of i and j as
// ConfigurationSpace::interpolate gives it, and each half so in turn (what the rounds'
// refinement put between waypoints the path still has). The motion from i to j then
// passes through the configurations of the path between them, up to rounding: a
// shortcut that is the path itself. scratch: room for one configuration.
bool midpoint_chain(const ConfigurationSpace& space, const std::vector<float>& path, std::size_t i,
                    std::size_t j, float* scratch) {
  const std::size_t span = j - i;
  if (span < 2 || (span & (span - 1)) != 0) return false;
  const int width = space.width();
  const std::size_t h = i + span / 2;
  space.interpolate(&path[i * width], &path[j * width], 0.5, scratch);
  if (!std::equal(scratch, scratch + width, &path[h * width])) return false;
  return span == 2 ||
         (midpoint_chain(space, path, i, h, scratch) && midpoint_chain(space, path, h, j, scratch));
}

// Shortcuts (i, j), j > i + 1, on `path`: all of them when few, else `candidates` at
// random; those the memo knows, or that are the path itself, with their verdicts.
Proposal propose(const ConfigurationSpace& space, const std::vector<float>& path, int candidates,
                 LocalPlanner* local, LocalPlanner* fine, bool certified, const ShortcutMemo& memo,
                 std::mt19937_64* rng) {
  const int width = space.width();
  Proposal p;
  const std::size_t m = path.size() / width;
  const std::size_t all = (m - 1) * (m - 2) / 2;
  if (all <= static_cast<std::size_t>(candidates)) {
    p.all_pairs = true;
    for (std::size_t i = 0; i + 2 < m; ++i)
      for (std::size_t j = i + 2; j < m; ++j) p.pairs.emplace_back(i, j);
  } else {
    std::set<std::pair<std::size_t, std::size_t>> chosen;
    std::uniform_int_distribution<std::size_t> pick(0, m - 1);
    while (chosen.size() < static_cast<std::size_t>(candidates)) {
      std::size_t i = pick(*rng), j = pick(*rng);
      if (i > j) std::swap(i, j);
      if (j >= i + 2) chosen.emplace(i, j);
    }
    p.pairs.assign(chosen.begin(), chosen.end());
  }
  const std::size_t n = p.pairs.size();
  p.from.resize(n * width);
  p.to.resize(n * width);
  p.segments.resize(n);
  p.fine_segments.resize(n);
  p.known.assign(n, -1);
  p.known_second.assign(n, 0);
  // Samples at the coarse resolution, and at the fine one together with the coarse ones
  // that are not among them.
  std::size_t coarse_samples = 0, at_once_samples = 0;
  std::vector<std::size_t> coarse_not_in_fine;  // shortcuts whose coarse samples fine's miss
  std::vector<float> scratch(width);
  for (std::size_t k = 0; k < n; ++k) {
    std::copy_n(&path[p.pairs[k].first * width], width, &p.from[k * width]);
    std::copy_n(&path[p.pairs[k].second * width], width, &p.to[k * width]);
    // Certified, a shortcut is certified itself: the path's motions are not taken for it.
    if (!certified &&
        midpoint_chain(space, path, p.pairs[k].first, p.pairs[k].second, scratch.data())) {
      p.known[k] = 0;
      p.known_second[k] = 1;
      continue;
    }
    if (const ShortcutMemo::Verdicts* v = memo.find(&p.from[k * width], &p.to[k * width])) {
      if (v->coarse == 1 || v->second == 1) {
        p.known[k] = 1;
        continue;
      }
      if (v->coarse == 0) {
        p.known[k] = 0;
        p.known_second[k] = v->second == 0;
        continue;
      }
    }
    p.checked.push_back(k);
    p.segments[k] = local->segments(&p.from[k * width], &p.to[k * width]);
    p.fine_segments[k] = fine->segments(&p.from[k * width], &p.to[k * width]);
    coarse_samples += p.segments[k] - 1;
    at_once_samples += p.fine_segments[k] - 1;
    if (p.fine_segments[k] % p.segments[k] != 0) {
      at_once_samples += p.segments[k] - 1;
      coarse_not_in_fine.push_back(k);
    }
  }
  p.fine_at_once = !certified && at_once_samples <= fine->one_batch_samples() &&
                   at_once_samples < coarse_samples + local->configurations_per_call_cost();
  if (p.fine_at_once) p.coarse_too = std::move(coarse_not_in_fine);
  return p;
}

// Appends the motions that check a proposal's shortcuts: each at the resolution it is
// first checked at, then the coarse_too ones at the coarse resolution.
void append_checks(const Proposal& p, int width, std::vector<float>* a, std::vector<float>* b,
                   std::vector<int>* segments) {
  const std::vector<int>& first = p.fine_at_once ? p.fine_segments : p.segments;
  for (const std::size_t k : p.checked) {
    a->insert(a->end(), &p.from[k * width], &p.from[(k + 1) * width]);
    b->insert(b->end(), &p.to[k * width], &p.to[(k + 1) * width]);
    segments->push_back(first[k]);
  }
  for (const std::size_t k : p.coarse_too) {
    a->insert(a->end(), &p.from[k * width], &p.from[(k + 1) * width]);
    b->insert(b->end(), &p.to[k * width], &p.to[(k + 1) * width]);
    segments->push_back(p.segments[k]);
  }
}

// Each shortcut's verdict from those of the motions append_checks gave, the known ones
// as known; those checked go into the memo (checked at once at the fine resolution, a
// shortcut free there passed both checks).
std::vector<std::uint8_t> shortcut_verdicts(const Proposal& p, const std::uint8_t* checks,
                                            int width, ShortcutMemo* memo) {
  std::vector<std::uint8_t> invalid(p.pairs.size(), 0);
  for (std::size_t k = 0; k < p.pairs.size(); ++k) invalid[k] = p.known[k] == 1;
  for (std::size_t c = 0; c < p.checked.size(); ++c) invalid[p.checked[c]] = checks[c];
  for (std::size_t c = 0; c < p.coarse_too.size(); ++c)
    if (checks[p.checked.size() + c]) invalid[p.coarse_too[c]] = 1;
  for (const std::size_t k : p.checked) {
    ShortcutMemo::Verdicts& v = memo->at(&p.from[k * width], &p.to[k * width]);
    v.coarse = invalid[k] ? 1 : 0;
    if (p.fine_at_once && !invalid[k]) v.second = 0;
  }
  return invalid;
}

// The waypoints on the way that ends at the last one (by `parent`), first to last.
std::vector<std::size_t> kept_waypoints(const std::vector<std::size_t>& parent) {
  std::vector<std::size_t> kept;
  for (std::size_t j = parent.size() - 1;; j = parent[j]) {
    kept.push_back(j);
    if (j == 0) break;
  }
  std::reverse(kept.begin(), kept.end());
  return kept;
}

// The path through the kept waypoints of `path`, with a midpoint in every segment when
// `refine` (so that the next round can cut corners closer).
std::vector<float> kept_path(const ConfigurationSpace& space, const std::vector<float>& path,
                             const std::vector<std::size_t>& kept, bool refine) {
  const int width = space.width();
  std::vector<float> next;
  std::vector<float> mid(width);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const float* q = &path[kept[k] * width];
    if (k > 0 && refine) {
      space.interpolate(&path[kept[k - 1] * width], q, 0.5, mid.data());
      next.insert(next.end(), mid.begin(), mid.end());
    }
    next.insert(next.end(), q, q + width);
  }
  return next;
}

}  // namespace

std::mt19937_64 shortcut_generator(std::uint64_t seed) {
  return std::mt19937_64(seed ^ 0x5bd1e995u);
}

double path_length(const ConfigurationMetric& metric, const std::vector<float>& path, int width) {
  double length = 0;
  const std::size_t m = path.size() / width;
  for (std::size_t i = 1; i < m; ++i)
    length += configuration_distance(metric, &path[(i - 1) * width], &path[i * width]);
  return length;
}

namespace {

// The rounds, each taken shortcut checked with `fine`, or certified by `certify` where
// given; the path after each round appended to `history` where given. False where the
// stop ended them (the path then as it was before the round).
bool shortcut_rounds(const ConfigurationSpace& space, LocalPlanner* local, LocalPlanner* fine,
                     CertifiedMotions* certify, int rounds, int candidates, std::mt19937_64* rng,
                     std::vector<float>* path, std::vector<std::vector<float>>* history = nullptr) {
  const int width = space.width();
  const ConfigurationMetric& metric = local->metric();
  // Where calls cost more than samples, the next round's shortcuts are proposed on the
  // path this round gives if the shortcuts it takes pass their fine check, and checked
  // in the same call as that fine check; if one fails, that proposal is dropped (and
  // the generator set back), so the result is the same either way.
  const bool pipelined = !certify && local->configurations_per_call_cost() > 0;
  ShortcutMemo memo(width);
  Proposal ahead;  // the next round's shortcuts, already checked
  std::vector<std::uint8_t> ahead_invalid;
  bool have_ahead = false;
  // Rounds in a row that shortened the path by less than kGain: two end the rounds (the
  // path has settled; each round costs a call). One is not enough: a round's midpoints
  // may let the next cut a corner (MotionBenchMaker's box: no gain, then 15 %).
  constexpr double kGain = 1e-3;
  int idle_rounds = 0;
  double length = path_length(metric, *path, width);
  for (int round = 0; round < rounds && idle_rounds < 2; ++round) {
    const std::size_t m = path->size() / width;
    if (m < 3) break;
    Proposal p;
    std::vector<std::uint8_t> invalid;
    if (have_ahead) {
      p = std::move(ahead);
      invalid = std::move(ahead_invalid);
      have_ahead = false;
    } else {
      p = propose(space, *path, candidates, local, fine, certify != nullptr, memo, rng);
      std::vector<float> a, b;
      std::vector<int> segments;
      append_checks(p, width, &a, &b, &segments);
      std::vector<std::uint8_t> checks(segments.size());
      if (!local->check_motions(a.data(), b.data(), segments.size(), segments.data(),
                                checks.data()))
        break;
      invalid = shortcut_verdicts(p, checks.data(), width, &memo);
    }
    const bool refine = round + 1 < rounds;  // midpoints, unless the path has too many
    auto d = [&](std::size_t i, std::size_t j) {
      return static_cast<double>(
          configuration_distance(metric, &(*path)[i * width], &(*path)[j * width]));
    };
    // Shortest way through the waypoints in order, over the path's own segments and the
    // shortcuts valid so far; the shortcuts it takes are checked again at the fine
    // resolution, and those failing drop out, until the way holds only certified ones.
    // Passed the second check: known to, or checked at once at the fine resolution.
    std::vector<std::uint8_t> certified(p.pairs.size());
    for (std::size_t k = 0; k < p.pairs.size(); ++k)
      certified[k] = p.known[k] == -1 ? p.fine_at_once : p.known_second[k];
    std::vector<std::size_t> parent(m, 0), via(m, kNone);
    while (true) {
      std::vector<std::vector<std::size_t>> into(m);  // valid shortcuts ending at j
      for (std::size_t k = 0; k < p.pairs.size(); ++k)
        if (!invalid[k]) into[p.pairs[k].second].push_back(k);
      std::vector<double> best(m, std::numeric_limits<double>::infinity());
      best[0] = 0;
      for (std::size_t j = 1; j < m; ++j) {
        best[j] = best[j - 1] + d(j - 1, j);
        parent[j] = j - 1;
        via[j] = kNone;
        for (const std::size_t k : into[j]) {
          const std::size_t i = p.pairs[k].first;
          const double c = best[i] + d(i, j);
          if (c < best[j]) {
            best[j] = c;
            parent[j] = i;
            via[j] = k;
          }
        }
      }
      std::vector<std::size_t> unchecked;
      for (std::size_t j = m - 1; j > 0; j = parent[j])
        if (via[j] != kNone && !certified[via[j]]) unchecked.push_back(via[j]);
      if (unchecked.empty()) break;
      // The fine check of the way's shortcuts, and (pipelined) the next round's
      // shortcuts on the path this way would give.
      std::vector<float> a, b;
      std::vector<int> segments;
      for (const std::size_t k : unchecked) {
        a.insert(a.end(), &p.from[k * width], &p.from[(k + 1) * width]);
        b.insert(b.end(), &p.to[k * width], &p.to[(k + 1) * width]);
        segments.push_back(p.fine_segments[k]);
      }
      const std::mt19937_64 rng_before = *rng;
      Proposal next;
      bool with_next = false;
      if (pipelined && round + 1 < rounds) {
        const std::vector<std::size_t> kept = kept_waypoints(parent);
        const bool refined = refine && 2 * kept.size() <= kMaxWaypoints;
        if (kept.size() < m || refined) {  // there will be a next round
          const std::vector<float> if_passed = kept_path(space, *path, kept, refined);
          if (if_passed.size() / width >= 3) {
            next = propose(space, if_passed, candidates, local, fine, false, memo, rng);
            append_checks(next, width, &a, &b, &segments);
            with_next = true;
          }
        }
      }
      std::vector<std::uint8_t> fails(segments.size());
      const bool checked =
          certify     ? certify->check_motions(a.data(), b.data(), segments.size(), fails.data())
          : pipelined ? local->check_motions(a.data(), b.data(), segments.size(), segments.data(),
                                             fails.data())
                      : fine->check_motions(a.data(), b.data(), segments.size(), segments.data(),
                                            fails.data());
      if (!checked) return false;  // stopped: the path as it was
      bool all_passed = true;
      for (std::size_t u = 0; u < unchecked.size(); ++u) {
        const std::size_t k = unchecked[u];
        memo.at(&p.from[k * width], &p.to[k * width]).second = fails[u] ? 1 : 0;
        if (fails[u]) {
          invalid[unchecked[u]] = 1;
          all_passed = false;
        } else {
          certified[unchecked[u]] = 1;
        }
      }
      if (with_next && all_passed) {
        ahead = std::move(next);
        ahead_invalid = shortcut_verdicts(ahead, fails.data() + unchecked.size(), width, &memo);
        have_ahead = true;
      } else if (with_next) {
        // Dropped; its verdicts are facts all the same.
        shortcut_verdicts(next, fails.data() + unchecked.size(), width, &memo);
        *rng = rng_before;
      }
    }
    const std::vector<std::size_t> kept = kept_waypoints(parent);
    const bool refined = refine && 2 * kept.size() <= kMaxWaypoints;
    const bool shorter = kept.size() < m;
    std::vector<float> next_path = kept_path(space, *path, kept, refined);
    // The same path again after a round of every shortcut: the rounds after it would be
    // this one again (the same proposals, verdicts and way), to the same end.
    const bool settled = p.all_pairs && next_path == *path;
    path->swap(next_path);
    if (history) history->push_back(*path);
    if ((!shorter && !refined) || settled) break;
    const double new_length = path_length(metric, *path, width);
    idle_rounds = new_length < length * (1 - kGain) ? 0 : idle_rounds + 1;
    length = new_length;
  }
  return true;
}

}  // namespace

ShortcutRounds run_shortcut_rounds(const ConfigurationSpace& space, LocalPlanner* local,
                                   LocalPlanner* fine, int rounds, int candidates,
                                   std::mt19937_64* rng, const std::vector<float>& path) {
  ShortcutRounds done;
  done.given = path;
  done.rng_before = *rng;
  done.shortened = path;
  done.stopped = !shortcut_rounds(space, local, fine, nullptr, rounds, candidates, rng,
                                  &done.shortened, &done.history);
  return done;
}

double certify_shortcut_rounds(const ConfigurationSpace& space, LocalPlanner* local,
                               LocalPlanner* fine, CertifiedMotions* certify, int rounds,
                               int candidates, const ShortcutRounds& done, bool shortened_failed,
                               std::mt19937_64* rng, std::vector<float>* path) {
  const int width = space.width();
  const ConfigurationMetric& metric = local->metric();
  *path = done.given;
  if (done.stopped || done.shortened == done.given)  // stopped, or nothing shorter
    return path_length(metric, *path, width);
  // Whether each path passes whole: its segments (waypoint i to i + 1) in one call.
  const auto certified_whole = [&](const std::vector<const std::vector<float>*>& paths,
                                   std::vector<std::uint8_t>* passed) {
    std::vector<float> from, to;
    for (const std::vector<float>* p : paths) {
      from.insert(from.end(), p->begin(), p->end() - width);
      to.insert(to.end(), p->begin() + width, p->end());
    }
    std::vector<std::uint8_t> invalid(from.size() / width);
    if (!certify->check_motions(from.data(), to.data(), invalid.size(), invalid.data()))
      return false;
    passed->assign(paths.size(), 1);
    for (std::size_t i = 0, segment = 0; i < paths.size(); ++i) {
      for (std::size_t s = 0; s + 1 < paths[i]->size() / width; ++s)
        if (invalid[segment++]) (*passed)[i] = 0;
    }
    return true;
  };
  std::vector<std::uint8_t> passed;
  if (!shortened_failed) {
    if (!certified_whole({&done.shortened}, &passed)) return path_length(metric, *path, width);
    if (passed[0]) {
      *path = done.shortened;
      return path_length(metric, *path, width);
    }
  }
  std::vector<const std::vector<float>*> earlier;  // latest first
  for (std::size_t r = done.history.size(); r-- > 0;)
    if (done.history[r] != done.shortened) earlier.push_back(&done.history[r]);
  if (!earlier.empty() && !certified_whole(earlier, &passed))
    return path_length(metric, *path, width);
  for (std::size_t i = 0; i < earlier.size(); ++i) {
    if (passed[i]) {
      *path = *earlier[i];
      return path_length(metric, *path, width);
    }
  }
  *rng = done.rng_before;
  shortcut_rounds(space, local, fine, certify, rounds, candidates, rng, path);
  return path_length(metric, *path, width);
}

double shortcut_path(const ConfigurationSpace& space, LocalPlanner* local, LocalPlanner* fine,
                     CertifiedMotions* certify, int rounds, int candidates, std::mt19937_64* rng,
                     std::vector<float>* path) {
  if (certify == nullptr) {
    shortcut_rounds(space, local, fine, nullptr, rounds, candidates, rng, path);
    return path_length(local->metric(), *path, space.width());
  }
  // Certified: the rounds with `fine`'s checks (pipelined where calls cost more than
  // samples), then the path they give certified whole, in one certification: a few calls
  // where certifying each round's shortcuts took several calls a round. Where a segment
  // fails (free at fine's samples, not certified: a shortcut grazing an obstacle between
  // them), the paths of the rounds before are certified, all in one certification, and
  // the last that passes whole is taken; where none does, the rounds again from the
  // path given, each shortcut certified.
  const ShortcutRounds done =
      run_shortcut_rounds(space, local, fine, rounds, candidates, rng, *path);
  return certify_shortcut_rounds(space, local, fine, certify, rounds, candidates, done, false, rng,
                                 path);
}

}  // namespace gplanner
