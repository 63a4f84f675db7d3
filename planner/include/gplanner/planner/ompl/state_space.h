#pragma once
// A scene's configuration space as an OMPL state space, with the planner's metric:
// - a rigid robot: ompl::base::SE3StateSpace (position weighted by the position weight,
//   SO(3) by twice the rotation weight, since OMPL's SO(3) distance is half the
//   rotation angle);
// - otherwise a compound space: the base (SE3 or SE2) when it moves, then one subspace
//   per planned joint in scene order (SO2 for continuous joints, a bounded 1-D real
//   vector space for the others), each weighted by the joint weight.
// Distances, interpolation, the largest extent and so the motion resolution
// (edge_resolution, as the longest valid segment fraction) equal the planner's own.

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateSpace.h>

namespace gplanner {

struct Scene;

namespace ompl_adapters {

ompl::base::StateSpacePtr make_state_space(const Scene& scene);

// Conversions between an OMPL state of make_state_space(scene) and a configuration row
// (shape [scene.space.width()]). States, like rows, are in the scene frame: for a
// scene far from the world origin (Scene::p_WS not zero) their base position is
// relative to scene.space.row_origin (ConfigurationSpace::from_file_values converts).
void state_to_row(const Scene& scene, const ompl::base::State* state, float* row);

// Throws std::invalid_argument, saying what differs and naming `who` (the adapter being
// made), unless `si` is a space information whose state space is laid out as
// make_state_space(scene)'s (the same kinds of subspaces, in the same order, of the same
// dimensions): the adapters convert states by that layout, and another would be read
// out of bounds.
void require_scene_state_space(const Scene& scene, const ompl::base::SpaceInformationPtr& si,
                               const char* who);
void row_to_state(const Scene& scene, const float* row, ompl::base::State* state);

}  // namespace ompl_adapters
}  // namespace gplanner
