#include "gplanner/planner/planning/planner_choice.h"

#include <stdexcept>

#include "gplanner/planner/scene/scene.h"

namespace gplanner {
const char* planner_name(PlannerKind kind) {
  switch (kind) {
    case PlannerKind::kLazyPrm:
      return "lazyprm";
    case PlannerKind::kPrm:
      return "prm";
    case PlannerKind::kRrtConnect:
      return "rrtconnect";
    case PlannerKind::kAuto:
      break;
  }
  return "auto";
}

bool parse_planner(const std::string& name, PlannerKind* kind) {
  for (const PlannerKind k :
       {PlannerKind::kAuto, PlannerKind::kLazyPrm, PlannerKind::kPrm, PlannerKind::kRrtConnect}) {
    if (name == planner_name(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

const char* planner_names() { return "auto, lazyprm, prm, rrtconnect"; }

bool keeps_roadmap(PlannerKind kind) { return kind != PlannerKind::kRrtConnect; }

ChosenPlanner::ChosenPlanner(const Scene& scene, CollisionChecker* checker,
                             NeighborFinder* neighbors, PlannerKind kind, bool with_roadmap,
                             const PlanOptions& options)
    : asked_(kind), used_(kind) {
  if (kind == PlannerKind::kAuto) {
    const bool rigid_body =
        scene.space.base != BaseType::kFixed && scene.space.planned_joints.empty();
    if (with_roadmap) {
      used_ = PlannerKind::kLazyPrm;
      reason_ = "a roadmap is loaded, saved or sized";
    } else if (rigid_body) {
      used_ = PlannerKind::kLazyPrm;
      reason_ = "a rigid body flying free";
    } else {
      used_ = PlannerKind::kRrtConnect;
      reason_ = "a robot with joints, a single query";
    }
  }
  if (used_ == PlannerKind::kRrtConnect) {
    tree_ = std::make_unique<TreePlanner>(scene, checker, options);
    return;
  }
  if (neighbors == nullptr) throw std::invalid_argument("ChosenPlanner: no k-NN for a roadmap");
  roadmap_ = std::make_unique<RoadmapPlanner>(
      scene, checker, neighbors,
      used_ == PlannerKind::kPrm ? RoadmapStrategy::kPrm : RoadmapStrategy::kLazyPrm, options);
}

ChosenPlanner::~ChosenPlanner() = default;

PlanResult ChosenPlanner::solve(const float* start, const float* goal) {
  return tree_ ? tree_->solve(start, goal) : roadmap_->solve(start, goal);
}

}  // namespace gplanner
