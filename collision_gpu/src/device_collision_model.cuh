#pragma once
// A collision model's arrays on the device, uploaded once, and the one place that hands
// out the view kernels read (the host model's view with every array pointer moved to
// the device's copy; as lbvh's get_device_repr()).

#include <cstdint>

#include "gplanner/collision_gpu/model_view.h"
#include "gplanner/common/cuda_memory.cuh"

namespace gplanner {

class DeviceCollisionModel {
 public:
  explicit DeviceCollisionModel(const FlatCollisionModel& host) : host_(host) {
    links_.upload(host.links);
    link_bodies_.upload(host.link_bodies);
    link_spheres_.upload(host.link_spheres);
    nodes_.upload(host.nodes);
    triangles_.upload(host.triangles);
    pair_a_.upload(host.pair_a);
    pair_b_.upload(host.pair_b);
    pair_ancestor_.upload(host.pair_ancestor);
    link_solids_.upload(host.link_solids);
    components_.upload(host.solids.components);
    component_tree_.upload(host.solids.tree);
    solid_nodes_.upload(host.solids.nodes);
    solid_triangles_.upload(host.solids.triangles);
  }

  // The view of the model for kernels: sizes and poses as the host model's, arrays on
  // the device (no clearances: a call sets its own).
  CollisionModelView view() const {
    CollisionModelView view = host_.view();
    view.links = links_.get();
    view.link_bodies = link_bodies_.get();
    view.link_spheres = link_spheres_.get();
    view.nodes = nodes_.get();
    view.triangles = triangles_.get();
    view.pair_a = pair_a_.get();
    view.pair_b = pair_b_.get();
    view.pair_ancestor = pair_ancestor_.get();
    view.link_solids = link_solids_.get();
    view.solids = {components_.get(), component_tree_.get(), solid_nodes_.get(),
                   solid_triangles_.get()};
    view.clearances = nullptr;
    return view;
  }

 private:
  const FlatCollisionModel& host_;
  cuda::DeviceBuffer<LinkKinematics> links_;
  cuda::DeviceBuffer<BodyRange> link_bodies_;
  cuda::DeviceBuffer<LinkSphere> link_spheres_;
  cuda::DeviceBuffer<BvhNode> nodes_;
  cuda::DeviceBuffer<BvhTriangle> triangles_;
  cuda::DeviceBuffer<std::int32_t> pair_a_, pair_b_, pair_ancestor_;
  cuda::DeviceBuffer<BodySolids> link_solids_;
  cuda::DeviceBuffer<Component> components_;
  cuda::DeviceBuffer<ComponentNode> component_tree_;
  cuda::DeviceBuffer<BvhNode> solid_nodes_;
  cuda::DeviceBuffer<BvhTriangle> solid_triangles_;
};

}  // namespace gplanner
