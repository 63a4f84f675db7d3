#include "gplanner/planner/ompl/state_space.h"

#include <stdexcept>
#include <string>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>

#include <cmath>

#include "gplanner/planner/scene/scene.h"

namespace gplanner::ompl_adapters {
namespace {

namespace ob = ompl::base;

bool has_joints(const Scene& scene) { return !scene.space.planned_joints.empty(); }

// The base subspace's state inside `state` (which may be the base itself).
const ob::State* base_state(const Scene& scene, const ob::State* state) {
  return has_joints(scene) ? state->as<ob::CompoundState>()->components[0] : state;
}
ob::State* base_state(const Scene& scene, ob::State* state) {
  return has_joints(scene) ? state->as<ob::CompoundState>()->components[0] : state;
}

}  // namespace

ob::StateSpacePtr make_state_space(const Scene& scene) {
  const ConfigurationSpace& space = scene.space;
  ob::StateSpacePtr base;
  if (space.base == BaseType::kFloating) {
    auto se3 = std::make_shared<ob::SE3StateSpace>();
    ob::RealVectorBounds bounds(3);
    for (int k = 0; k < 3; ++k) {
      bounds.setLow(k, space.base_min[k]);
      bounds.setHigh(k, space.base_max[k]);
    }
    se3->setBounds(bounds);
    se3->setSubspaceWeight(0, scene.planner.distance_weights.position);
    se3->setSubspaceWeight(1, 2 * scene.planner.distance_weights.rotation);
    base = se3;
  } else if (space.base == BaseType::kPlanar) {
    auto se2 = std::make_shared<ob::SE2StateSpace>();
    ob::RealVectorBounds bounds(2);
    for (int k = 0; k < 2; ++k) {
      bounds.setLow(k, space.base_min[k]);
      bounds.setHigh(k, space.base_max[k]);
    }
    se2->setBounds(bounds);
    se2->setSubspaceWeight(0, scene.planner.distance_weights.position);
    se2->setSubspaceWeight(1, scene.planner.distance_weights.rotation);
    base = se2;
  }
  ob::StateSpacePtr result;
  if (!has_joints(scene)) {
    result = base;
  } else {
    auto compound = std::make_shared<ob::CompoundStateSpace>();
    if (base) compound->addSubspace(base, 1.0);
    const double w = scene.planner.distance_weights.joint;
    for (std::size_t j = 0; j < space.planned_joints.size(); ++j) {
      const std::string& name = scene.robot.joints[space.planned_joints[j]].name;
      ob::StateSpacePtr joint;
      if (space.continuous[j]) {
        joint = std::make_shared<ob::SO2StateSpace>();
      } else {
        auto line = std::make_shared<ob::RealVectorStateSpace>(1);
        line->setBounds(space.lower[j], space.upper[j]);
        joint = line;
      }
      joint->setName(name);
      compound->addSubspace(joint, w);
    }
    compound->lock();
    result = compound;
  }
  if (!result) {
    // A fixed base and no planned joints: nothing to plan, but a valid (0-D) space.
    result = std::make_shared<ob::RealVectorStateSpace>(0);
  }
  result->setLongestValidSegmentFraction(scene.planner.edge_resolution);
  return result;
}

namespace {

// A state space's layout: its kind and dimension, then its subspaces' (one level down, as
// make_state_space builds them).
std::string layout(const ob::StateSpace& space) {
  std::string text = std::to_string(space.getType()) + ":" + std::to_string(space.getDimension());
  if (space.isCompound()) {
    const auto* compound = space.as<ob::CompoundStateSpace>();
    text += "(";
    for (unsigned int i = 0; i < compound->getSubspaceCount(); ++i)
      text += (i ? "," : "") + layout(*compound->getSubspace(i));
    text += ")";
  }
  return text;
}

}  // namespace

void require_scene_state_space(const Scene& scene, const ob::SpaceInformationPtr& si,
                               const char* who) {
  if (!si) throw std::invalid_argument(std::string(who) + ": no space information (null)");
  const ob::StateSpacePtr expected = make_state_space(scene);
  const ob::StateSpacePtr& given = si->getStateSpace();
  if (!given || layout(*given) != layout(*expected)) {
    throw std::invalid_argument(
        std::string(who) + ": the space information's state space (" +
        (given ? given->getName() + ", " + std::to_string(given->getDimension()) + " dimensions"
               : std::string("none")) +
        ") is not laid out as scene '" + scene.name + "' plans (" +
        std::to_string(expected->getDimension()) +
        " dimensions); make it with gplanner::ompl_adapters::make_state_space(scene)");
  }
}

void state_to_row(const Scene& scene, const ob::State* state, float* row) {
  const ConfigurationSpace& space = scene.space;
  const ob::State* base = base_state(scene, state);
  if (space.base == BaseType::kFloating) {
    const auto* s = base->as<ob::SE3StateSpace::StateType>();
    const ob::SO3StateSpace::StateType& r = s->rotation();
    const float values[] = {float(s->getX()), float(s->getY()), float(s->getZ()), float(r.w),
                            float(r.x),       float(r.y),       float(r.z)};
    std::copy(values, values + 7, row);
  } else if (space.base == BaseType::kPlanar) {
    const auto* s = base->as<ob::SE2StateSpace::StateType>();
    row[0] = float(s->getX());
    row[1] = float(s->getY());
    row[2] = float(s->getYaw());
  }
  if (!has_joints(scene)) return;
  const auto* compound = state->as<ob::CompoundState>();
  const int first = space.base == BaseType::kFixed ? 0 : 1;
  const int offset = space.base_width();
  for (std::size_t j = 0; j < space.planned_joints.size(); ++j) {
    const ob::State* joint = compound->components[first + j];
    row[offset + j] = space.continuous[j]
                          ? float(joint->as<ob::SO2StateSpace::StateType>()->value)
                          : float(joint->as<ob::RealVectorStateSpace::StateType>()->values[0]);
  }
}

void row_to_state(const Scene& scene, const float* row, ob::State* state) {
  const ConfigurationSpace& space = scene.space;
  ob::State* base = base_state(scene, state);
  if (space.base == BaseType::kFloating) {
    auto* s = base->as<ob::SE3StateSpace::StateType>();
    s->setXYZ(row[0], row[1], row[2]);
    // Normalised in double: OMPL holds quaternions to unit length within 1e-9, tighter
    // than float rows can.
    ob::SO3StateSpace::StateType& r = s->rotation();
    const double w = row[3], x = row[4], y = row[5], z = row[6];
    const double norm = std::sqrt(w * w + x * x + y * y + z * z);
    r.w = w / norm;
    r.x = x / norm;
    r.y = y / norm;
    r.z = z / norm;
  } else if (space.base == BaseType::kPlanar) {
    auto* s = base->as<ob::SE2StateSpace::StateType>();
    s->setXY(row[0], row[1]);
    s->setYaw(row[2]);
  }
  if (!has_joints(scene)) return;
  auto* compound = state->as<ob::CompoundState>();
  const int first = space.base == BaseType::kFixed ? 0 : 1;
  const int offset = space.base_width();
  for (std::size_t j = 0; j < space.planned_joints.size(); ++j) {
    ob::State* joint = compound->components[first + j];
    if (space.continuous[j]) {
      joint->as<ob::SO2StateSpace::StateType>()->value = row[offset + j];
    } else {
      joint->as<ob::RealVectorStateSpace::StateType>()->values[0] = row[offset + j];
    }
  }
}

}  // namespace gplanner::ompl_adapters
