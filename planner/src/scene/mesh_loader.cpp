#include "gplanner/planner/scene/mesh_loader.h"

#include <tinyxml2.h>

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "gplanner/common/physical_memory.h"
#include "gplanner/planner/scene/input_file.h"
#include "guarded_io_system.h"
#include "mesh_file_check.h"

namespace gplanner {
namespace {

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return out;
}

// Appends the triangles of `node` and its children. A node whose transform (with its
// parents', the file's unit among them) is singular would flatten its meshes: an
// InputError, as a zero scale is.
void collect_triangles(const aiScene& scene, const aiNode& node, const Eigen::Matrix4d& X_parent,
                       TriangleMesh* mesh, const SourceLocation& where, const std::string& what) {
  const Eigen::Matrix4d X_node = X_parent * to_eigen(node.mTransformation);
  const double determinant = X_node.topLeftCorner<3, 3>().determinant();
  if (node.mNumMeshes > 0 && !(std::isfinite(determinant) && determinant != 0)) {
    throw InputError(where, what + " is flattened by its own transforms: node '" +
                                node.mName.C_Str() +
                                "' (or the file's unit) scales an axis by zero; fix the file");
  }
  const bool mirrored = determinant < 0;
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
    collect_triangles(scene, *node.mChildren[c], X_node, mesh, where, what);
  }
}

// The up axis a COLLADA file declares in <asset><up_axis>, and the line saying it (0
// when none does: COLLADA's default is Y_UP).
struct UpAxis {
  std::string axis = "Y_UP";
  int line = 0;
};

UpAxis collada_up_axis(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  UpAxis up;
  // <asset> is the first child of <COLLADA>; read it alone rather than the whole file.
  const std::size_t begin = text.find("<asset");
  const std::size_t end = text.find("</asset>", begin);
  if (begin == std::string::npos || end == std::string::npos) return up;
  tinyxml2::XMLDocument asset;
  if (asset.Parse(text.data() + begin, end + 8 - begin) != tinyxml2::XML_SUCCESS) return up;
  const tinyxml2::XMLElement* element = asset.RootElement()->FirstChildElement("up_axis");
  if (element == nullptr || element->GetText() == nullptr) return up;
  std::istringstream value(element->GetText());
  value >> up.axis;
  up.line = static_cast<int>(std::count(text.begin(), text.begin() + begin, '\n')) +
            element->GetLineNum();
  return up;
}

// ROS and hpp-fcl read COLLADA coordinates as written, z up, whatever axis the file
// declares (docs/scenes.md, "COLLADA up axes"); so do we, and say so for other axes.
void note_ignored_up_axis(const std::string& path, std::vector<std::string>* notices) {
  const UpAxis up = collada_up_axis(path);
  if (up.axis == "Z_UP") return;
  const std::string turn = up.axis == "X_UP" ? "a quarter turn about y (rpy=\"0 -1.5708 0\")"
                                             : "a quarter turn about x (rpy=\"1.5708 0 0\")";
  const std::string notice =
      path + (up.line > 0 ? ":" + std::to_string(up.line) : std::string()) + ": COLLADA up axis " +
      up.axis + (up.line > 0 ? "" : " (COLLADA's default: the file declares none)") +
      " ignored: the mesh is read as written, z up, as ROS (MoveIt, RViz) and hpp-fcl read it; "
      "if it really is " +
      up.axis + ", turn it where it is placed: " + turn;
  if (std::find(notices->begin(), notices->end(), notice) == notices->end()) {
    notices->push_back(notice);
  }
}

bool is_collada(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".dae";
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

namespace {

// The memory reading a mesh file takes, estimated from what it holds before assimp reads
// it (which can take tens of seconds): a binary STL says its triangle count in its
// header; other formats are estimated by their size (a text OBJ holds about 40 bytes a
// triangle). Per triangle: assimp's copies, ours, the BVHs and FCL's models, about 600
// bytes. Refused, naming the estimate, where it exceeds what a run may use (half of the
// machine's memory) or the process's address-space limit, or where an STL holds more
// triangles than a mesh may.
void check_mesh_memory(const std::string& path, std::uintmax_t size, const SourceLocation& where,
                       const std::string& what) {
  constexpr double kBytesPerTriangle = 600;
  double triangles = static_cast<double>(size) / 40;
  std::ifstream in(path, std::ios::binary);
  char header[84];
  if (in.read(header, sizeof header)) {
    std::uint32_t count = 0;
    std::memcpy(&count, header + 80, 4);  // little-endian, as STL is and the machine
    if (84 + 50 * static_cast<std::uintmax_t>(count) == size) {  // a binary STL
      if (count > kMaxMeshTriangles) {
        throw InputError(where,
                         what + " has " + std::to_string(count) + " triangles, more than the " +
                             std::to_string(kMaxMeshTriangles) + " a mesh may have; simplify it");
      }
      triangles = count;
    }
  }
  const double bytes = triangles * kBytesPerTriangle;
  const std::size_t address_space = address_space_limit_bytes();
  if (address_space > 0 && bytes > static_cast<double>(address_space)) {
    throw InputError(where, what + " (" + memory_text(static_cast<double>(size)) + ", about " +
                                std::to_string(static_cast<long long>(triangles)) +
                                " triangles) would need about " + memory_text(bytes) +
                                " to read and check, more than the process's address-space "
                                "limit (ulimit -v) of " +
                                memory_text(static_cast<double>(address_space)) +
                                "; simplify the mesh or raise the limit");
  }
  if (!fits_in_memory(bytes)) {
    throw InputError(where, what + " (" + memory_text(static_cast<double>(size)) + ", about " +
                                std::to_string(static_cast<long long>(triangles)) +
                                " triangles) would need about " + memory_text(bytes) +
                                " to read and check, more than half of this machine's " +
                                memory_text(physical_memory_bytes()) +
                                " of memory; simplify the mesh");
  }
}

}  // namespace

TriangleMesh load_mesh(const std::string& path, const Eigen::Vector3d& scale,
                       const SourceLocation& referenced_from, std::vector<std::string>* notices,
                       std::vector<std::string>* files_read) {
  const std::string what = "mesh '" + path + "'";
  const std::uintmax_t size = check_input_file(path, kMeshFile, referenced_from);
  if (!scale.allFinite() || (scale.array() == 0).any()) {
    throw InputError(referenced_from, "mesh scale must be finite and non-zero on every axis");
  }
  check_mesh_file(path, size, referenced_from, what);
  check_mesh_memory(path, size, referenced_from, what);
  Assimp::Importer importer;
  // assimp opens the mesh and whatever it names through this (the importer owns it).
  auto* const io_system = new GuardedIOSystem;
  importer.SetIOHandler(io_system);
  // COLLADA files say which axis is up, and assimp would turn them to y up; ROS and
  // hpp-fcl read them as written, z up, and so do we (with a notice for other axes).
  // Units (<unit meter=...>) stay applied, as RViz and Gazebo apply them.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  if (notices && is_collada(path)) note_ignored_up_axis(path, notices);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // ValidateDataStructure runs before the other steps, which trust the importer's
  // indices (a PLY face naming a vertex past the last crashed JoinIdenticalVertices).
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_ValidateDataStructure | aiProcess_Triangulate |
                                  aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (files_read) {
    files_read->insert(files_read->end(), io_system->files_read().begin(),
                       io_system->files_read().end());
  }
  if (!io_system->refusal().empty()) {
    throw InputError(referenced_from,
                     what + " names a file that cannot be read: " + io_system->refusal());
  }
  if (scene == nullptr || scene->mRootNode == nullptr) {
    const std::string error = importer.GetErrorString();
    // SortByPType removes points and lines; a file holding nothing else is left empty.
    // (ValidateDataStructure says the same in its words.)
    if (error.find("No meshes remaining") != std::string::npos ||
        error.find("contains no faces") != std::string::npos ||
        error.find("mNumMeshes is 0") != std::string::npos) {
      throw InputError(referenced_from, what +
                                            " has no triangles (only points or lines); give a "
                                            "mesh with at least one face");
    }
    throw InputError(referenced_from, what + " cannot be read: " + error +
                                          "; give a mesh file (STL, OBJ, COLLADA, ...) with at "
                                          "least one triangle");
  }
  std::size_t triangles = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) triangles += scene->mMeshes[m]->mNumFaces;
  if (triangles > kMaxMeshTriangles) {
    throw InputError(referenced_from,
                     what + " has " + std::to_string(triangles) + " triangles, more than the " +
                         std::to_string(kMaxMeshTriangles) + " a mesh may have; simplify it");
  }
  TriangleMesh mesh;
  collect_triangles(*scene, *scene->mRootNode, Eigen::Matrix4d::Identity(), &mesh, referenced_from,
                    what);
  if (mesh.triangles.size() > kMaxMeshTriangles) {
    throw InputError(referenced_from, what + " places " + std::to_string(mesh.triangles.size()) +
                                          " triangles through its nodes, more than the " +
                                          std::to_string(kMaxMeshTriangles) +
                                          " a mesh may have; simplify it");
  }
  validate_mesh(&mesh, referenced_from, what);
  for (Eigen::Vector3d& p : mesh.vertices) p = p.cwiseProduct(scale);
  if (scale.prod() < 0) {
    for (Eigen::Vector3i& t : mesh.triangles) std::swap(t[1], t[2]);
  }
  return mesh;
}

}  // namespace gplanner
