#include "gplanner/planner/planning/goal_distances.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <new>
#include <queue>
#include <utility>

#include "a_star.h"
#include "gplanner/common/parallel_for.h"
#include "uninitialized_array.h"

namespace gplanner {

// Each vertex's edges in one array, in the order of the edges' indices (Roadmap::edges_at's
// order, so that ties settle as there): a settle reads a vertex's row in one run instead
// of an index list and then each edge where it lies. (The piano's roadmap of 32,000
// vertices and 377,000 edges: a Dijkstra 8.5 ms through edges_at, 5.7 ms through rows.)
struct GoalDistances::Rows {
  using Entry = WayEdge;
  std::uint64_t id = 0;  // which rows a GPU holds: a number no other rows have had
  const Roadmap* roadmap = nullptr;
  std::size_t vertices = 0, edges = 0;
  std::vector<std::size_t> first;  // row v is entries[first[v], first[v + 1])
  // Not value-initialised: the threads that fill it write every entry, each touching its
  // part of the memory first (zeroing 12 MB on one thread first took longer than filling
  // it on all: the piano's roadmap of 32,000 milestones).
  detail::UninitializedArray<Entry> entries;
};

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::uint32_t kNone = ~std::uint32_t(0);
// Vertices whose rows a thread reads at a time.
constexpr std::size_t kRowGrain = 512;
// Edges whose usability a thread reads at a time (below it, the calling thread alone).
constexpr std::size_t kUsableGrain = 65536;

using Entry = std::pair<double, std::uint32_t>;  // (cost, vertex)
using MinQueue = std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>>;

}  // namespace

void GoalDistances::read_rows(const Roadmap& roadmap) {
  if (rows_ && rows_->roadmap == &roadmap && rows_->vertices == roadmap.vertex_count() &&
      rows_->edges == roadmap.edge_count())
    return;
  static std::atomic<std::uint64_t> rows_made{0};
  auto rows = std::make_shared<Rows>();
  rows->id = ++rows_made;
  rows->roadmap = &roadmap;
  rows->vertices = roadmap.vertex_count();
  rows->edges = roadmap.edge_count();
  rows->first.assign(rows->vertices + 1, 0);
  for (std::size_t v = 0; v < rows->vertices; ++v)
    rows->first[v + 1] = rows->first[v] + roadmap.edges_at(v).size();
  rows->entries = detail::uninitialized_array<Rows::Entry>(rows->first.back());
  // Each row as edges_at lists the vertex's edges (in index order), on the host's threads
  // (a roadmap of 32,000 milestones took 2 to 4 ms a round on one). The reads of the
  // edges miss the caches: all threads, in parts of kRowGrain vertices (in parts of
  // 4,096 the piano's 32,000 made 8 parts for the H200 host's 16 cores: 6.3 ms).
  Rows& r = *rows;
  parallel_for(
      r.vertices, resolve_thread_count(0),
      [&](std::size_t begin, std::size_t end, int) {
        for (std::size_t v = begin; v < end; ++v) {
          std::size_t i = r.first[v];
          for (const std::uint32_t e : roadmap.edges_at(v)) {
            const RoadmapEdge& edge = roadmap.edge(e);
            new (&r.entries[i++]) Rows::Entry{edge.a == v ? edge.b : edge.a, e, edge.length};
          }
        }
      },
      kRowGrain);
  rows_ = std::move(rows);
}

namespace {

// Dijkstra from the queued vertices outwards over the usable edges: each vertex is
// settled at its least cost, and its edges lower their other ends' costs. (After
// remove_edges seeds it, only the affected vertices can be lowered: the others keep the
// costs of ways that still exist.) Polls `should_stop` every kStopPoll vertices; false
// when it said to stop, the costs then unfinished.
template <class RowsT>
bool settle(const RowsT& rows, const std::vector<std::uint8_t>& usable,
            const std::function<bool()>& should_stop, MinQueue* open, std::vector<double>* cost,
            std::vector<std::uint32_t>* via) {
  constexpr std::size_t kStopPoll = 4096;
  for (std::size_t popped = 1; !open->empty(); ++popped) {
    if (popped % kStopPoll == 0 && should_stop && should_stop()) return false;
    const auto [c, v] = open->top();
    open->pop();
    if (c > (*cost)[v]) continue;
    for (std::size_t i = rows.first[v]; i < rows.first[v + 1]; ++i) {
      const auto& entry = rows.entries[i];
      if (!usable[entry.edge]) continue;
      const double through_v = c + entry.length;
      if (through_v < (*cost)[entry.other]) {
        (*cost)[entry.other] = through_v;
        (*via)[entry.other] = entry.edge;
        open->emplace(through_v, entry.other);
      }
    }
  }
  return true;
}

}  // namespace

void GoalDistances::compute(const Roadmap& roadmap, std::uint32_t goal, bool valid_edges_only) {
  read_rows(roadmap);
  valid_edges_only_ = valid_edges_only;
  goal_ = goal;
  usable_.resize(roadmap.edge_count());
  parallel_for(
      usable_.size(), resolve_thread_count(0),
      [&](std::size_t begin, std::size_t end, int) {
        for (std::size_t e = begin; e < end; ++e)
          usable_[e] = usable(roadmap.edge(e), valid_edges_only);
      },
      kUsableGrain);
  cost_.assign(roadmap.vertex_count(), kInf);
  via_.assign(roadmap.vertex_count(), kNone);
  affected_.assign(roadmap.vertex_count(), 0);
  exact_ = true;
  if (compute_on_gpu(goal)) return;
  MinQueue open;
  cost_[goal] = 0;
  open.emplace(0, goal);
  stopped_ = !settle(*rows_, usable_, should_stop_, &open, &cost_, &via_);
}

bool GoalDistances::compute_on_gpu(std::uint32_t goal) {
  const Rows& rows = *rows_;
  if (gpu_ == nullptr || rows.vertices < kGpuVertices) return false;
  GpuWayCosts::Outcome outcome = GpuWayCosts::Outcome::kNoFirstEdge;
  try {
    if (gpu_->roadmap_key() != rows.id)
      gpu_->set_roadmap(rows.id, rows.first.data(), rows.vertices, rows.entries.get(), rows.edges);
    outcome = gpu_->compute(goal, usable_.data(), cost_.data(), via_.data(), should_stop_);
  } catch (const std::exception&) {
    gpu_ = nullptr;  // the GPU failed (its memory, most likely): the host from now on
  }
  switch (outcome) {
    case GpuWayCosts::Outcome::kDone:
      stopped_ = false;
      return true;
    case GpuWayCosts::Outcome::kStopped:
      stopped_ = true;
      return true;
    case GpuWayCosts::Outcome::kNoFirstEdge:
      break;
  }
  std::fill(cost_.begin(), cost_.end(), kInf);  // the host's Dijkstra from scratch
  std::fill(via_.begin(), via_.end(), kNone);
  return false;
}

std::size_t GoalDistances::remove_edges(const Roadmap& roadmap,
                                        const std::vector<std::uint32_t>& edges,
                                        std::size_t max_affected) {
  if (!rows_) return 0;  // nothing computed yet: no costs to repair
  const Rows& rows = *rows_;
  // The affected vertices: those whose first edge to the goal was removed, and then
  // every vertex whose way goes through an affected one (the tree of ways below them,
  // found through each affected vertex's edges: w hangs below v when w's first edge is
  // the edge from v).
  affected_.resize(cost_.size(), 0);  // all 0 between calls
  std::vector<std::uint32_t>& found = found_;
  found.clear();
  for (const std::uint32_t e : edges) {
    const RoadmapEdge& edge = roadmap.edge(e);
    if (usable(edge, valid_edges_only_)) continue;
    usable_[e] = 0;
    for (const std::uint32_t v : {edge.a, edge.b}) {
      if (via_[v] == e && !affected_[v]) {
        affected_[v] = 1;
        found.push_back(v);
      }
    }
  }
  // Past half of all vertices, a Dijkstra from the goal over all costs less than
  // repairing them (finding them, then seeding each from its neighbours): on lazy PRM's
  // roadmaps an invalid edge near the goal leaves most of the roadmap affected. On the
  // GPU, past an eighth.
  const bool on_gpu = gpu_ != nullptr && cost_.size() >= kGpuVertices;
  const std::size_t most = cost_.size() / (on_gpu ? 8 : 2);
  for (std::size_t i = 0; i < found.size(); ++i) {
    if (found.size() > std::min(max_affected, most)) {
      for (const std::uint32_t u : found) affected_[u] = 0;
      if (found.size() > max_affected) {
        exact_ = false;
        return max_affected + 1;
      }
      compute(roadmap, goal_, valid_edges_only_);
      return cost_.size();
    }
    const std::uint32_t v = found[i];
    for (std::size_t j = rows.first[v]; j < rows.first[v + 1]; ++j) {
      const Rows::Entry& entry = rows.entries[j];
      if (via_[entry.other] == entry.edge && !affected_[entry.other]) {
        affected_[entry.other] = 1;
        found.push_back(entry.other);
      }
    }
  }
  // They start from their best neighbour whose cost holds, then settle among themselves
  // in cost order.
  MinQueue open;
  for (const std::uint32_t v : found) {
    cost_[v] = kInf;
    via_[v] = kNone;
    for (std::size_t j = rows.first[v]; j < rows.first[v + 1]; ++j) {
      const Rows::Entry& entry = rows.entries[j];
      if (!usable_[entry.edge] || affected_[entry.other]) continue;
      if (cost_[entry.other] + entry.length < cost_[v]) {
        cost_[v] = cost_[entry.other] + entry.length;
        via_[v] = entry.edge;
      }
    }
    if (via_[v] != kNone) open.emplace(cost_[v], v);
  }
  stopped_ = !settle(rows, usable_, should_stop_, &open, &cost_, &via_);
  for (const std::uint32_t v : found) affected_[v] = 0;
  return found.size();
}

void GoalDistances::set_unusable(const Roadmap& roadmap, const std::vector<std::uint32_t>& edges) {
  if (!rows_) return;
  for (const std::uint32_t e : edges) {
    const RoadmapEdge& edge = roadmap.edge(e);
    if (usable(edge, valid_edges_only_)) continue;
    usable_[e] = 0;
    if (via_[edge.a] == e || via_[edge.b] == e) exact_ = false;
  }
}

GraphPath GoalDistances::shortest_path(std::uint32_t start, std::size_t max_expanded,
                                       const std::function<bool()>& should_stop) const {
  if (!rows_) return {};
  const Rows& rows = *rows_;
  return detail::a_star(
      rows.vertices, start, goal_,
      [&](std::uint32_t v, const auto& visit) {
        for (std::size_t i = rows.first[v]; i < rows.first[v + 1]; ++i) {
          const Rows::Entry& entry = rows.entries[i];
          if (usable_[entry.edge]) visit(entry.edge, entry.other, entry.length);
        }
      },
      [&](std::uint32_t v) { return cost_[v]; }, max_expanded, should_stop);
}

}  // namespace gplanner
