#pragma once
// Collision meshes from files (STL, COLLADA, OBJ and whatever else assimp reads).

#include <string>
#include <vector>

#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/triangle_mesh.h"

namespace gplanner {

// Loads every triangle of `path` (node transforms and COLLADA units applied), scaled
// per axis by `scale` after loading. COLLADA coordinates are read as written, z up,
// whatever up axis the file declares, as ROS and hpp-fcl read them; a file declaring
// another axis (or none, which COLLADA takes as Y_UP) adds a line to `notices` (when
// given, once per file). A negative scale mirrors the mesh; the winding is flipped so
// that faces still point outward. Points and lines are ignored. Throws InputError
// naming `referenced_from` (the scene or URDF element naming the file) when the file
// is missing or unreadable, flattened by its own node transforms or unit (a zero
// scale), or fails validate_mesh.
TriangleMesh load_mesh(const std::string& path, const Eigen::Vector3d& scale,
                       const SourceLocation& referenced_from,
                       std::vector<std::string>* notices = nullptr);

// Checks a mesh handed over from elsewhere: finite coordinates, indices in range, at
// least one triangle; drops triangles that repeat a vertex index. Throws InputError.
void validate_mesh(TriangleMesh* mesh, const SourceLocation& where, const std::string& what);

}  // namespace gplanner
