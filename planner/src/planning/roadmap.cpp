#include "gplanner/planner/planning/roadmap.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "gplanner/common/parallel_for.h"
#include "gplanner/common/prefault.h"
#include "gplanner/knn_gpu/gpu_way_costs.h"

namespace gplanner {

std::uint32_t Roadmap::add_vertex(const float* q) {
  vertices_.insert(vertices_.end(), q, q + width_);
  adjacency_.emplace_back();
  return static_cast<std::uint32_t>(adjacency_.size() - 1);
}

namespace {
constexpr std::size_t kFirstEdgeRoom = 32;
// Fewer new edges than this are put in their ends' lists on the calling thread alone.
constexpr std::size_t kEdgesPerThread = 16384;
}  // namespace

long long Roadmap::add_edge(std::uint32_t a, std::uint32_t b, float length, EdgeState state) {
  if (a == b || find_edge(a, b) >= 0) return -1;
  return append_edge(a, b, length, state);
}

std::uint32_t Roadmap::append_edge(std::uint32_t a, std::uint32_t b, float length,
                                   EdgeState state) {
  if (a > b) std::swap(a, b);
  const auto e = static_cast<std::uint32_t>(edges_.size());
  edges_.push_back({a, b, length, state});
  // A milestone gets about twice k edges: room for that at its first, instead of the
  // five or six reallocations of doubling from one.
  for (const std::uint32_t v : {a, b}) {
    if (adjacency_[v].empty()) adjacency_[v].reserve(kFirstEdgeRoom);
    adjacency_[v].push_back(e);
  }
  return e;
}

void Roadmap::reserve_vertices(std::size_t vertices) {
  try {
    vertices_.reserve(vertices * static_cast<std::size_t>(width_));
    adjacency_.reserve(vertices);
  } catch (const std::exception&) {  // std::bad_alloc, std::length_error
  }
}

std::size_t Roadmap::append_edges(const RoadmapEdge* edges, std::size_t count) {
  const std::size_t first = edges_.size();
  // Copied in one run, into the room reserve_edges made with its pages mapped on the
  // host's threads first (only the room these take: a round's room for millions of
  // milestones, mapped all at once, took longer than a time limit's slice, and longer to
  // give back at the exit), then each put in order (a < b) on the host's threads.
  if (edges_.capacity() - first >= count)
    prefault_for_writing(edges_.data() + first, count * sizeof(RoadmapEdge));
  edges_.insert(edges_.end(), edges, edges + count);
  const std::size_t parts = count < kEdgesPerThread ? 1 : resolve_thread_count(0);
  parallel_for(
      count, static_cast<int>(parts),
      [&](std::size_t begin, std::size_t end, int) {
        for (std::size_t i = first + begin; i < first + end; ++i) {
          RoadmapEdge& edge = edges_[i];
          if (edge.a > edge.b) std::swap(edge.a, edge.b);
        }
      },
      kEdgesPerThread);
  // Each part of the vertices (a range) on a thread of its own: it goes through all the
  // new edges in order and gathers those at its vertices by vertex (a counting sort,
  // which keeps each vertex's edges in index order), then appends them vertex after
  // vertex. (Appending them as they came, to lists all over the roadmap, missed the
  // caches twice an edge: 6.5 ms for a round of 32,000 new milestones on the H200's host.)
  const std::size_t n = adjacency_.size();
  parallel_for(
      parts, static_cast<int>(parts),
      [&](std::size_t begin, std::size_t end, int) {
        std::vector<std::uint32_t> starts, gathered;
        for (std::size_t part = begin; part < end; ++part) {
          const std::size_t lo = part * n / parts, hi = (part + 1) * n / parts;
          auto in_part = [&](std::uint32_t v) { return v >= lo && v < hi; };
          starts.assign(hi - lo + 1, 0);
          for (std::size_t e = first; e < first + count; ++e) {
            for (const std::uint32_t v : {edges_[e].a, edges_[e].b})
              if (in_part(v)) ++starts[v - lo + 1];
          }
          for (std::size_t v = 1; v <= hi - lo; ++v) starts[v] += starts[v - 1];
          gathered.resize(starts[hi - lo]);
          for (std::size_t e = first; e < first + count; ++e) {
            for (const std::uint32_t v : {edges_[e].a, edges_[e].b})
              if (in_part(v)) gathered[starts[v - lo]++] = static_cast<std::uint32_t>(e);
          }
          // starts[v - lo] is now where v's run ends (and v + 1's begins).
          std::size_t run = 0;
          for (std::size_t v = lo; v < hi; ++v) {
            const std::size_t stop = starts[v - lo];
            if (stop == run) continue;
            std::vector<std::uint32_t>& list = adjacency_[v];
            if (list.empty()) list.reserve(std::max(kFirstEdgeRoom, stop - run));
            list.insert(list.end(), gathered.begin() + run, gathered.begin() + stop);
            run = stop;
          }
        }
      },
      1);
  return first;
}

long long Roadmap::find_edge(std::uint32_t a, std::uint32_t b) const {
  if (a == b || a >= adjacency_.size() || b >= adjacency_.size()) return -1;
  // The shorter list: a new milestone has about k edges, where a hub may have thousands.
  const std::uint32_t v = adjacency_[a].size() <= adjacency_[b].size() ? a : b;
  const std::uint32_t w = v == a ? b : a;
  for (const std::uint32_t e : adjacency_[v]) {
    const RoadmapEdge& edge = edges_[e];
    if (edge.a == w || edge.b == w) return e;
  }
  return -1;
}

double roadmap_bytes(std::size_t milestones, int width, int neighbors) {
  // Per vertex: its row, its adjacency list (add_edge's first room of 32 entries, or
  // about 2k), and the searches' costs, parents and marks (GoalDistances and A*) and
  // GoalDistances' row start; per edge (up to k a vertex): the edge, and its length,
  // neighbour index and whether it is new while made, and GoalDistances' two row entries
  // and usability.
  const double per_vertex = width * sizeof(float) + sizeof(std::vector<std::uint32_t>) +
                            std::max(32.0, 2.0 * neighbors) * sizeof(std::uint32_t) + 32.0 +
                            sizeof(std::size_t);
  const double per_edge = sizeof(RoadmapEdge) + sizeof(float) + sizeof(int) + sizeof(std::uint8_t) +
                          2 * sizeof(WayEdge) + sizeof(std::uint8_t);
  return static_cast<double>(milestones) * (per_vertex + neighbors * per_edge);
}

}  // namespace gplanner
