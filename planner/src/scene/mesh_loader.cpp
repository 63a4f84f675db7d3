#include "gplanner/planner/scene/mesh_loader.h"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <filesystem>
#include <fstream>

namespace gplanner {
namespace {

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return out;
}

void collect_triangles(const aiScene& scene, const aiNode& node, const Eigen::Matrix4d& X_parent,
                       TriangleMesh* mesh) {
  const Eigen::Matrix4d X_node = X_parent * to_eigen(node.mTransformation);
  const bool mirrored = X_node.topLeftCorner<3, 3>().determinant() < 0;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& part = *scene.mMeshes[node.mMeshes[m]];
    const int base = static_cast<int>(mesh->vertices.size());
    for (unsigned v = 0; v < part.mNumVertices; ++v) {
      const aiVector3D& p = part.mVertices[v];
      mesh->vertices.push_back((X_node * Eigen::Vector4d(p.x, p.y, p.z, 1)).head<3>());
    }
    for (unsigned f = 0; f < part.mNumFaces; ++f) {
      const aiFace& face = part.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no volume
      const int a = base + static_cast<int>(face.mIndices[0]);
      const int b = base + static_cast<int>(face.mIndices[1]);
      const int c = base + static_cast<int>(face.mIndices[2]);
      mesh->triangles.emplace_back(a, mirrored ? c : b, mirrored ? b : c);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    collect_triangles(scene, *node.mChildren[c], X_node, mesh);
  }
}

}  // namespace

void validate_mesh(TriangleMesh* mesh, const SourceLocation& where, const std::string& what) {
  for (const Eigen::Vector3d& p : mesh->vertices) {
    if (!p.allFinite()) {
      throw InputError(where, what + " has a NaN or infinite vertex coordinate; repair the mesh");
    }
  }
  const int n = static_cast<int>(mesh->vertices.size());
  for (const Eigen::Vector3i& t : mesh->triangles) {
    if ((t.array() < 0).any() || (t.array() >= n).any()) {
      throw InputError(where, what + " has a triangle index outside its vertex list");
    }
  }
  auto repeats_vertex = [](const Eigen::Vector3i& t) {
    return t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
  };
  mesh->triangles.erase(
      std::remove_if(mesh->triangles.begin(), mesh->triangles.end(), repeats_vertex),
      mesh->triangles.end());
  if (mesh->triangles.empty()) {
    throw InputError(where, what + " has no triangles; give a mesh with at least one face");
  }
}

TriangleMesh load_mesh(const std::string& path, const Eigen::Vector3d& scale,
                       const SourceLocation& referenced_from) {
  const std::string what = "mesh '" + path + "'";
  if (!std::filesystem::is_regular_file(path)) {
    throw InputError(referenced_from, what + " does not exist; fix the path");
  }
  if (!std::ifstream(path).good()) {
    throw InputError(referenced_from, what + " cannot be read; check its permissions");
  }
  if (!scale.allFinite() || (scale.array() == 0).any()) {
    throw InputError(referenced_from, "mesh scale must be finite and non-zero on every axis");
  }
  Assimp::Importer importer;
  // COLLADA files say which axis is up; ROS meshes are z-up whatever they declare, and
  // assimp would otherwise rotate them to y-up.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    const std::string error = importer.GetErrorString();
    // SortByPType removes points and lines; a file holding nothing else is left empty.
    if (error.find("No meshes remaining") != std::string::npos) {
      throw InputError(referenced_from, what +
                                            " has no triangles (only points or lines); give a "
                                            "mesh with at least one face");
    }
    throw InputError(referenced_from, what + " cannot be read: " + error);
  }
  TriangleMesh mesh;
  collect_triangles(*scene, *scene->mRootNode, Eigen::Matrix4d::Identity(), &mesh);
  validate_mesh(&mesh, referenced_from, what);
  for (Eigen::Vector3d& p : mesh.vertices) p = p.cwiseProduct(scale);
  if (scale.prod() < 0) {
    for (Eigen::Vector3i& t : mesh.triangles) std::swap(t[1], t[2]);
  }
  return mesh;
}

}  // namespace gplanner
