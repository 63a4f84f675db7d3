#pragma once
// Mesh files checked before assimp reads them (private to the mesh loader): what a file
// claims must fit what it holds, so that a small file cannot make assimp allocate
// gigabytes, recurse without end or overflow its stack.

#include <cstdint>
#include <string>

#include "gplanner/planner/scene/input_error.h"

namespace gplanner {

// The most nodes a COLLADA scene may expand to through <instance_node>, and how deep.
inline constexpr std::uint64_t kMaxColladaNodes = 100000;
inline constexpr int kMaxColladaDepth = 100;

// Checks the mesh file `path` of `size` bytes by its content: a PLY header's element
// counts must fit the bytes after it (at their smallest encoding); a COLLADA file's
// <instance_node> references must form no cycle and expand to at most kMaxColladaNodes
// nodes at most kMaxColladaDepth deep. Throws InputError at `where` naming `what`.
void check_mesh_file(const std::string& path, std::uintmax_t size, const SourceLocation& where,
                     const std::string& what);

}  // namespace gplanner
