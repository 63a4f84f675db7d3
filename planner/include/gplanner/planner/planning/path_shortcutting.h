#pragma once
// Batched path shortcutting: each round proposes many shortcuts between waypoints of
// the path (all of them when few), checks them in one batch with `local`, and keeps the
// shortest path through the valid ones (a shortest path over the waypoints in order),
// whose shortcuts are checked again with `fine` (dropping those that fail, until the
// path holds only shortcuts both passed); then puts a midpoint into every segment so
// that the next round can cut corners closer; two rounds in a row that shorten the path
// by less than 0.1 % end them early. Where the checker's calls cost more than
// samples (the GPU), the next round's shortcuts are checked in the same call as this
// round's fine check (dropped if that fails: the same path, fewer calls), and a round
// checks every shortcut at both resolutions in one call (fine's samples and those of
// `local` not among them: the verdicts of the two stages) where that adds fewer samples
// than a call costs: the path does not depend on what a call costs. A path valid at
// fine's resolution stays so. A shortcut is not checked where its verdicts are known:
// one over the midpoints the rounds put in (the path itself, up to rounding), or one with
// the same ends checked before in the same rounds. With `certify`, the
// path the rounds give is certified whole at the end (one certification, a few calls);
// where that fails, the last earlier round's path that passes whole (all certified in
// one certification), and where none does, the rounds again from the given path with
// each round's shortcuts certified instead of checked with `fine`: a certified path
// stays certified (a midpoint cuts a certified motion into two motions along the same
// configurations).
// Stops, with the path as it is, when `local`'s stop condition says so.

#include <cstdint>
#include <random>
#include <vector>

#include "gplanner/planner/planning/certified_motions.h"
#include "gplanner/planner/planning/local_planner.h"

namespace gplanner {

struct ConfigurationSpace;

// The shortcut rounds' generator for a plan of seed `seed`: their own, so that the
// rounds do not depend on how many draws the plan's time-sized batches made before.
std::mt19937_64 shortcut_generator(std::uint64_t seed);

// path: shape [waypoints, width], start and goal kept; returns the metric length after.
// certify: null, or the certified check that replaces fine's.
double shortcut_path(const ConfigurationSpace& space, LocalPlanner* local, LocalPlanner* fine,
                     CertifiedMotions* certify, int rounds, int candidates, std::mt19937_64* rng,
                     std::vector<float>* path);

// shortcut_path in two parts, for callers that certify the shortened path themselves
// (with other motions in the same calls) and, where it fails, go on without running the
// rounds again: run_shortcut_rounds is shortcut_path without `certify`, each round's
// path kept; certify_shortcut_rounds is what shortcut_path does with `certify` once the
// rounds have run (shortened_failed: the shortened path is known to fail its
// certification, so that only the earlier rounds' paths are certified). The given path
// must then be certified (a path it returns is the given one, an earlier round's, or
// one of certified shortcuts made from the given one); where the rounds run again,
// certified, *rng starts from done.rng_before.
struct ShortcutRounds {
  std::vector<float> given;                 // the path the rounds started from
  std::vector<float> shortened;             // the last round's path
  std::vector<std::vector<float>> history;  // each round's path, in order
  std::mt19937_64 rng_before;               // the generator before the rounds
  bool stopped = false;                     // the stop ended them (shortened: as it was)
};
ShortcutRounds run_shortcut_rounds(const ConfigurationSpace& space, LocalPlanner* local,
                                   LocalPlanner* fine, int rounds, int candidates,
                                   std::mt19937_64* rng, const std::vector<float>& path);
// Returns the metric length of *path, the path chosen.
double certify_shortcut_rounds(const ConfigurationSpace& space, LocalPlanner* local,
                               LocalPlanner* fine, CertifiedMotions* certify, int rounds,
                               int candidates, const ShortcutRounds& done, bool shortened_failed,
                               std::mt19937_64* rng, std::vector<float>* path);

// Metric length of a path (shape [waypoints, width]).
double path_length(const ConfigurationMetric& metric, const std::vector<float>& path, int width);

}  // namespace gplanner
