#pragma once
// A probabilistic roadmap: collision-free milestones and the straight-line edges between
// near ones, each edge unknown (lazy), valid or invalid. Its file is
// output/roadmap_file.h.

#include <cstdint>
#include <string>
#include <vector>

namespace gplanner {

struct Scene;

enum class EdgeState : std::uint8_t { kUnknown = 0, kValid = 1, kInvalid = 2 };

struct RoadmapEdge {
  std::uint32_t a = 0, b = 0;  // vertex indices, a < b
  float length = 0;            // metric distance
  EdgeState state = EdgeState::kUnknown;
};

// Whether a search may use the edge: never an invalid one, and with valid_edges_only
// (PRM) only a valid one.
inline bool usable(const RoadmapEdge& edge, bool valid_edges_only) {
  if (edge.state == EdgeState::kInvalid) return false;
  return !valid_edges_only || edge.state == EdgeState::kValid;
}

class Roadmap {
 public:
  explicit Roadmap(int width = 0) : width_(width) {}

  int width() const { return width_; }
  std::size_t vertex_count() const { return adjacency_.size(); }
  std::size_t edge_count() const { return edges_.size(); }
  const float* vertex(std::size_t i) const { return &vertices_[i * width_]; }
  const std::vector<float>& vertices() const { return vertices_; }  // shape [n, width]
  const std::vector<RoadmapEdge>& edges() const { return edges_; }
  RoadmapEdge& edge(std::size_t e) { return edges_[e]; }
  const RoadmapEdge& edge(std::size_t e) const { return edges_[e]; }
  // Edge indices at vertex v.
  const std::vector<std::uint32_t>& edges_at(std::size_t v) const { return adjacency_[v]; }

  std::uint32_t add_vertex(const float* q);
  // Adds the edge a-b unless it exists (or a == b); returns its index, or -1 when it was
  // not added.
  long long add_edge(std::uint32_t a, std::uint32_t b, float length,
                     EdgeState state = EdgeState::kUnknown);
  // Adds the edge a-b, which the caller knows the roadmap does not have (and a != b),
  // without add_edge's search for it (a scan of one end's edges); returns its index.
  // (Since 0.5.3: lazy PRM's new milestones, whose k nearest say which edges exist.)
  std::uint32_t append_edge(std::uint32_t a, std::uint32_t b, float length,
                            EdgeState state = EdgeState::kUnknown);
  // Appends `count` edges that the roadmap does not have (nor any twice), each a != b, in
  // their order, their ends' lists filled on the host's threads; returns the first one's
  // index. (Since 0.5.3; since 0.5.7 the room they take, where reserve_edges made it, is
  // mapped on the host's threads first: prefault_for_writing.)
  std::size_t append_edges(const RoadmapEdge* edges, std::size_t count);
  long long find_edge(std::uint32_t a, std::uint32_t b) const;
  // Room for this many edges in all.
  void reserve_edges(std::size_t edges) { edges_.reserve(edges); }
  // Room for this many vertices in all (since 0.5.3); none made where the allocation
  // fails (the roadmap then grows as vertices come).
  void reserve_vertices(std::size_t vertices);

 private:
  int width_;
  std::vector<float> vertices_;
  std::vector<RoadmapEdge> edges_;
  std::vector<std::vector<std::uint32_t>> adjacency_;
};

// About how many bytes a planner's roadmap of `milestones` vertices of `width` floats,
// each joined to its `neighbors` nearest, takes with the search's per-vertex state:
// estimated before growing it, so that a roadmap that would not fit is not begun.
double roadmap_bytes(std::size_t milestones, int width, int neighbors);

}  // namespace gplanner

// Deprecated since 0.2.0 (to be removed in 0.6): save_roadmap, load_roadmap and
// scene_fingerprint moved to gplanner/planner/output/roadmap_file.h; include that.
#include "gplanner/planner/output/roadmap_file.h"
