#include "gplanner/collision_gpu/model_view.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "gplanner/collision_gpu/detail/containment.h"
#include "gplanner/collision_gpu/detail/query.h"

namespace gplanner {
namespace {

BodyRange append_body(const Bvh& bvh, std::vector<BvhNode>* nodes,
                      std::vector<BvhTriangle>* triangles) {
  BodyRange range;
  if (bvh.empty()) return range;
  range.node_offset = static_cast<std::int32_t>(nodes->size());
  range.triangle_offset = static_cast<std::int32_t>(triangles->size());
  nodes->insert(nodes->end(), bvh.nodes.begin(), bvh.nodes.end());
  triangles->insert(triangles->end(), bvh.triangles.begin(), bvh.triangles.end());
  return range;
}

// The deepest link that both a and b are (or hang from); links[l].parent < l.
std::int32_t deepest_common_ancestor(const std::vector<LinkKinematics>& links, std::int32_t a,
                                     std::int32_t b) {
  while (a != b) {
    if (a > b) {
      a = links[a].parent;
    } else {
      b = links[b].parent;
    }
    if (a < 0 || b < 0) return 0;  // the root: every link hangs from it
  }
  return a;
}

}  // namespace

std::size_t CollisionModel::triangle_count() const {
  std::size_t count = 0;
  for (const Bvh& bvh : link_bvhs) count += bvh.triangles.size();
  return count;
}

int bvh_depth(const Bvh& bvh) {
  if (bvh.empty()) return 0;
  int deepest = 0;
  std::vector<std::pair<int, int>> stack{{0, 1}};
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, depth);
    if (!bvh.nodes[node].is_leaf()) {
      stack.push_back({bvh.nodes[node].child, depth + 1});
      stack.push_back({bvh.nodes[node].child + 1, depth + 1});
    }
  }
  return deepest;
}

FlatCollisionModel::FlatCollisionModel(const CollisionModel& model)
    : base(model.base),
      width(model.width),
      threshold(model.threshold),
      links(model.links),
      pair_a(model.pair_a),
      pair_b(model.pair_b) {
  std::memcpy(X_WB, model.X_WB, sizeof(X_WB));
  if (links.empty() || static_cast<int>(links.size()) > detail::kMaxLinks) {
    throw std::invalid_argument("a collision model needs 1 to " +
                                std::to_string(detail::kMaxLinks) + " links, not " +
                                std::to_string(links.size()));
  }
  if (model.link_bvhs.size() != links.size()) {
    throw std::invalid_argument("a collision model needs one BVH (possibly empty) per link");
  }
  int deepest_link = 0;
  for (const Bvh& bvh : model.link_bvhs) {
    link_bodies.push_back(append_body(bvh, &nodes, &triangles));
    link_spheres.push_back(
        {{bvh.sphere_center[0], bvh.sphere_center[1], bvh.sphere_center[2]}, bvh.sphere_radius});
    deepest_link = std::max(deepest_link, bvh_depth(bvh));
  }
  environment = append_body(model.environment, &nodes, &triangles);
  for (std::size_t p = 0; p < pair_a.size(); ++p) {
    if (pair_a[p] < 0 || pair_b[p] < 0 || pair_a[p] >= static_cast<int>(links.size()) ||
        pair_b[p] >= static_cast<int>(links.size())) {
      throw std::invalid_argument("a checked link pair names a link the model does not have");
    }
    pair_ancestor.push_back(deepest_common_ancestor(links, pair_a[p], pair_b[p]));
  }
  traversal_depth = deepest_link + std::max(deepest_link, bvh_depth(model.environment));
  if (traversal_depth >= detail::kStackSize) {
    throw std::invalid_argument("BVHs too deep for the traversal stack of " +
                                std::to_string(detail::kStackSize) + " entries");
  }

  if (!model.link_components.empty() && model.link_components.size() != links.size()) {
    throw std::invalid_argument("a collision model needs components for every link or none");
  }
  for (std::size_t l = 0; l < links.size(); ++l) {
    link_solids.push_back(
        model.link_components.empty() ? BodySolids{} : solids.add_body(model.link_components[l]));
  }
  environment_solids = solids.add_body(model.environment_components);
  if (2 * solids.deepest_tree >= detail::kComponentStackSize ||
      solids.deepest_bvh >= detail::kRayStackSize) {
    throw std::invalid_argument(
        "solid components too many or too deep for the stacks of the "
        "containment step");
  }
  const auto either_holds = [](BodySolids a, BodySolids b) {
    return (a.solids >= 0 && b.points >= 0) || (b.solids >= 0 && a.points >= 0);
  };
  for (std::size_t l = 0; l < links.size(); ++l) {
    if (link_bodies[l].node_offset >= 0 && environment.node_offset >= 0)
      containment = containment || either_holds(link_solids[l], environment_solids);
  }
  for (std::size_t p = 0; p < pair_a.size(); ++p)
    containment = containment || either_holds(link_solids[pair_a[p]], link_solids[pair_b[p]]);
}

CollisionModelView FlatCollisionModel::view() const {
  CollisionModelView v{};
  v.base = base;
  std::memcpy(v.X_WB, X_WB, sizeof(X_WB));
  v.width = width;
  v.threshold = threshold;
  v.margin = 2 * threshold;
  v.link_count = static_cast<std::int32_t>(links.size());
  v.links = links.data();
  v.link_bodies = link_bodies.data();
  v.link_spheres = link_spheres.data();
  v.environment = environment;
  v.nodes = nodes.data();
  v.triangles = triangles.data();
  v.pair_count = static_cast<std::int32_t>(pair_a.size());
  v.pair_a = pair_a.data();
  v.pair_b = pair_b.data();
  v.pair_ancestor = pair_ancestor.data();
  v.containment = containment ? 1 : 0;
  v.link_solids = link_solids.data();
  v.environment_solids = environment_solids;
  v.solids = solids.view();
  return v;
}

}  // namespace gplanner
