#pragma once
// Collision meshes from files (STL, COLLADA, OBJ and whatever else assimp reads).

#include <string>

#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/triangle_mesh.h"

namespace gplanner {

// Loads every triangle of `path` (node transforms applied; COLLADA kept z-up, as ROS
// does), scaled per axis by `scale` after loading. A negative scale mirrors the mesh;
// the winding is flipped so that faces still point outward. Points and lines are
// ignored. Throws InputError naming `referenced_from` (the scene or URDF element
// naming the file) when the file is missing or unreadable, has no triangles, or holds
// a NaN or infinite coordinate.
TriangleMesh load_mesh(const std::string& path, const Eigen::Vector3d& scale,
                       const SourceLocation& referenced_from);

// Checks a mesh handed over from elsewhere: finite coordinates, indices in range, at
// least one triangle; drops triangles that repeat a vertex index. Throws InputError.
void validate_mesh(TriangleMesh* mesh, const SourceLocation& where, const std::string& what);

}  // namespace gplanner
