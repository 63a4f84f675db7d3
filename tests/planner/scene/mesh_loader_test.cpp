// Meshes through assimp (STL, OBJ, COLLADA), scales and primitives.

#include "gplanner/planner/scene/mesh_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "test_support.h"

namespace gplanner {
namespace {

constexpr double kPi = 3.14159265358979323846;

double signed_volume(const TriangleMesh& mesh) {
  double volume = 0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6;
  }
  return volume;
}

// A unit cube [0,1]^3 with an extra tip on +x, so mirror images are distinguishable.
std::string binary_stl(const TriangleMesh& mesh) {
  std::string data(80, '\0');
  const std::uint32_t count = static_cast<std::uint32_t>(mesh.triangles.size());
  data.append(reinterpret_cast<const char*>(&count), 4);
  for (const Eigen::Vector3i& t : mesh.triangles) {
    float values[12] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < 3; ++c)
        values[3 + 3 * k + c] = static_cast<float>(mesh.vertices[t[k]][c]);
    }
    data.append(reinterpret_cast<const char*>(values), sizeof(values));
    data.append(2, '\0');
  }
  return data;
}

std::string obj_text(const TriangleMesh& mesh) {
  std::string text = "o part\n";
  for (const Eigen::Vector3d& p : mesh.vertices) {
    text += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " +
            std::to_string(p.z()) + "\n";
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    text += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
            std::to_string(t[2] + 1) + "\n";
  }
  return text;
}

// COLLADA in centimetres, declared Y_UP: ROS keeps meshes z-up whatever they say, but
// honours the unit.
std::string dae_text(const TriangleMesh& mesh) {
  std::string positions, indices;
  for (const Eigen::Vector3d& p : mesh.vertices) {
    positions +=
        std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + " ";
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    indices += std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + " ";
  }
  const std::string nv = std::to_string(mesh.vertices.size());
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<asset><unit name="centimeter" meter="0.01"/><up_axis>Y_UP</up_axis></asset>
<library_geometries><geometry id="g"><mesh>
<source id="p"><float_array id="pa" count=")" +
         std::to_string(3 * mesh.vertices.size()) + R"(">)" + positions +
         R"(</float_array><technique_common><accessor source="#pa" count=")" + nv +
         R"(" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<triangles count=")" +
         std::to_string(mesh.triangles.size()) +
         R"("><input semantic="VERTEX" source="#v" offset="0"/><p>)" + indices +
         R"(</p></triangles></mesh></geometry></library_geometries>
<library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene></COLLADA>
)";
}

TriangleMesh test_shape() {
  TriangleMesh mesh = make_box(Eigen::Vector3d(1, 2, 3));
  for (Eigen::Vector3d& p : mesh.vertices) p += Eigen::Vector3d(0.5, 1, 1.5);  // [0,1]x[0,2]x[0,3]
  return mesh;
}

const SourceLocation kWhere{"scene.yaml", 7, "robot.mesh"};

TEST(MeshLoader, ReadsStlObjAndCollada) {
  testing::ScratchFolder scratch;
  const TriangleMesh shape = test_shape();
  for (const std::string name : {"shape.stl", "shape.STL", "shape.obj"}) {
    const std::string file =
        scratch.write(name, name.back() == 'j' ? obj_text(shape) : binary_stl(shape));
    const TriangleMesh mesh = load_mesh(file, Eigen::Vector3d::Ones(), kWhere);
    EXPECT_EQ(mesh.triangle_count(), 12u) << name;
    EXPECT_NEAR(signed_volume(mesh), 6.0, 1e-5) << name;
    EXPECT_LT((mesh.bounds().max() - Eigen::Vector3d(1, 2, 3)).norm(), 1e-5) << name;
  }
  const TriangleMesh dae =
      load_mesh(scratch.write("shape.dae", dae_text(shape)), Eigen::Vector3d::Ones(), kWhere);
  EXPECT_EQ(dae.triangle_count(), 12u);
  EXPECT_LT((dae.bounds().max() - Eigen::Vector3d(0.01, 0.02, 0.03)).norm(), 1e-7)
      << "expected centimetres applied and z kept up: " << dae.bounds().max().transpose();
}

TEST(MeshLoader, ScalesAndMirrorsKeepingFacesOutward) {
  testing::ScratchFolder scratch;
  const std::string file = scratch.write("shape.stl", binary_stl(test_shape()));
  const TriangleMesh scaled = load_mesh(file, Eigen::Vector3d(2, 1, 0.5), kWhere);
  EXPECT_NEAR(signed_volume(scaled), 6.0, 1e-5);
  EXPECT_LT((scaled.bounds().max() - Eigen::Vector3d(2, 2, 1.5)).norm(), 1e-5);
  // Talos mirrors meshes with scale="1 -1 1": the volume must stay positive.
  const TriangleMesh mirrored = load_mesh(file, Eigen::Vector3d(1, -1, 1), kWhere);
  EXPECT_NEAR(signed_volume(mirrored), 6.0, 1e-5);
  EXPECT_LT((mirrored.bounds().min() - Eigen::Vector3d(0, -2, 0)).norm(), 1e-5);
}

TEST(MeshLoader, RejectsMissingEmptyAndNonFiniteMeshes) {
  testing::ScratchFolder scratch;
  auto message = [&](const std::string& file) {
    try {
      load_mesh(file, Eigen::Vector3d::Ones(), kWhere);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string missing = message(scratch.path() + "/nothing.stl");
  EXPECT_NE(missing.find("scene.yaml:7: robot.mesh"), std::string::npos) << missing;
  EXPECT_NE(missing.find("does not exist"), std::string::npos) << missing;
  const std::string points =
      message(scratch.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1\nl 1 2\n"));
  EXPECT_NE(points.find("robot.mesh"), std::string::npos) << points;
  EXPECT_NE(points.find("points.obj"), std::string::npos) << points;

  TriangleMesh nan = test_shape();
  nan.vertices[3].x() = NAN;
  EXPECT_THROW(validate_mesh(&nan, kWhere, "test mesh"), InputError);
  TriangleMesh degenerate;
  degenerate.vertices = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()};
  degenerate.triangles = {Eigen::Vector3i(0, 1, 1)};
  EXPECT_THROW(validate_mesh(&degenerate, kWhere, "test mesh"), InputError);
  TriangleMesh bad_index = test_shape();
  bad_index.triangles[0][1] = 99;
  EXPECT_THROW(validate_mesh(&bad_index, kWhere, "test mesh"), InputError);
}

TEST(MeshLoader, PrimitivesContainTheExactShape) {
  const TriangleMesh box = make_box(Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(box.triangle_count(), 12u);
  EXPECT_NEAR(signed_volume(box), 6.0, 1e-12);
  // Every face plane of the tessellated sphere and cylinder lies outside the exact shape.
  auto min_face_distance = [](const TriangleMesh& mesh, const Eigen::Vector3d& axis_mask) {
    double smallest = 1e9;
    for (const Eigen::Vector3i& t : mesh.triangles) {
      const Eigen::Vector3d a = mesh.vertices[t[0]], b = mesh.vertices[t[1]],
                            c = mesh.vertices[t[2]];
      const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
      EXPECT_GT(n.dot(a), 0) << "face points inward";
      if (n.cwiseProduct(axis_mask).norm() > 0.99) smallest = std::min(smallest, n.dot(a));
    }
    return smallest;
  };
  const TriangleMesh sphere = make_sphere(0.5);
  EXPECT_GT(signed_volume(sphere), 4.0 / 3 * kPi * 0.125);
  EXPECT_GE(min_face_distance(sphere, Eigen::Vector3d::Ones()), 0.5 - 1e-3);
  const TriangleMesh cylinder = make_cylinder(0.5, 2.0);
  EXPECT_GT(signed_volume(cylinder), kPi * 0.25 * 2.0);
  EXPECT_GE(min_face_distance(cylinder, Eigen::Vector3d(1, 1, 0)), 0.5 - 1e-12);
}

}  // namespace
}  // namespace gplanner
