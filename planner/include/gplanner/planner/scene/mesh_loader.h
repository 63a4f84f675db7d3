#pragma once
// Collision meshes from files (STL, COLLADA, OBJ and whatever else assimp reads).

#include <string>
#include <vector>

#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/input_limits.h"
#include "gplanner/planner/scene/triangle_mesh.h"

namespace gplanner {

// Loads every triangle of `path` (node transforms and COLLADA units applied), scaled
// per axis by `scale` after loading. COLLADA coordinates are read as written, z up,
// whatever up axis the file declares, as ROS and hpp-fcl read them; a file declaring
// another axis (or none, which COLLADA takes as Y_UP) adds a line to `notices` (when
// given, once per file). A negative scale mirrors the mesh; the winding is flipped so
// that faces still point outward. Points and lines are ignored. The file, and every
// file assimp opens for it (an OBJ's .mtl, ...), must be a readable regular file of at
// most kMeshFile.max_bytes (input_file.h); each is appended to `files_read` (when
// given). Throws InputError naming `referenced_from` (the scene or URDF element naming
// the file) when a file is missing (the mesh itself), not a regular file, too large or
// unreadable; when a PLY header claims more than the file holds, a COLLADA file's
// <instance_node>s form a cycle or expand too far (mesh_file_check.h); when the mesh
// has more than kMaxMeshTriangles (input_limits.h) triangles, is flattened by its own node transforms or
// unit (a zero scale), or fails validate_mesh.
TriangleMesh load_mesh(const std::string& path, const Eigen::Vector3d& scale,
                       const SourceLocation& referenced_from,
                       std::vector<std::string>* notices = nullptr,
                       std::vector<std::string>* files_read = nullptr);

// Checks a mesh handed over from elsewhere: finite coordinates, indices in range, at
// least one triangle; drops triangles that repeat a vertex index. Throws InputError.
void validate_mesh(TriangleMesh* mesh, const SourceLocation& where, const std::string& what);

}  // namespace gplanner
