// Meshes through assimp (STL, OBJ, COLLADA), scales and primitives.

#include "gplanner/planner/scene/mesh_loader.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/scene.h"
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

// COLLADA with `asset` (by default: in centimetres, declared Y_UP) and `node` inside
// the node instancing the mesh (a transform).
const char* const kCentimetresYUp =
    R"(<asset><unit name="centimeter" meter="0.01"/><up_axis>Y_UP</up_axis></asset>)";

std::string dae_text(const TriangleMesh& mesh, const std::string& asset = kCentimetresYUp,
                     const std::string& node = "") {
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
)" + asset +
         R"(
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
<library_visual_scenes><visual_scene id="s"><node id="n">)" +
         node +
         R"(<instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
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

// COLLADA up axes: MoveIt (geometric_shapes clears the root transform, in which
// assimp turns a file to y up, as RViz does) and hpp-fcl (which skips the root node's
// transform) read the coordinates as written, z up, whatever the file declares. So do
// we; a file declaring another axis (or none: COLLADA's default is Y_UP) is noticed.
TEST(MeshLoader, ColladaUpAxesAreIgnoredWithANotice) {
  testing::ScratchFolder scratch;
  TriangleMesh triangle;
  triangle.vertices = {{1, 2, 3}, {4, 2, 3}, {1, 6, 3}};
  triangle.triangles = {{0, 1, 2}};
  // A node transform below the root still applies: +(10, 20, 30) cm.
  const std::string translate = "<translate>10 20 30</translate>";
  const std::vector<Eigen::Vector3d> expected = {
      {0.11, 0.22, 0.33}, {0.14, 0.22, 0.33}, {0.11, 0.26, 0.33}};
  struct Case {
    std::string up_axis;  // the <up_axis> element, if any
    std::string notice;   // what the notice must say; empty: no notice
  };
  const std::vector<Case> cases = {
      {"<up_axis>Z_UP</up_axis>", ""},
      {"<up_axis>Y_UP</up_axis>", "COLLADA up axis Y_UP ignored"},
      {"<up_axis> X_UP </up_axis>", "COLLADA up axis X_UP ignored"},
      {"", "COLLADA up axis Y_UP (COLLADA's default: the file declares none) ignored"}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.up_axis);
    const std::string asset =
        "<asset>\n<unit name=\"centimeter\" meter=\"0.01\"/>\n" + c.up_axis + "\n</asset>";
    const std::string file = scratch.write("part.dae", dae_text(triangle, asset, translate));
    std::vector<std::string> notices;
    const TriangleMesh mesh = load_mesh(file, Eigen::Vector3d::Ones(), kWhere, &notices);
    ASSERT_EQ(mesh.vertices.size(), 3u);
    for (int v = 0; v < 3; ++v) {
      EXPECT_LT((mesh.vertices[v] - expected[v]).norm(), 1e-7)
          << "vertex " << v << ": " << mesh.vertices[v].transpose();
    }
    if (c.notice.empty()) {
      EXPECT_TRUE(notices.empty()) << notices.front();
      continue;
    }
    ASSERT_EQ(notices.size(), 1u);
    // FILE:LINE (the <up_axis> line: the fifth) when the file declares an axis.
    const std::string where = file + (c.up_axis.empty() ? ": " : ":5: ");
    EXPECT_EQ(notices[0].rfind(where + c.notice, 0), 0u) << notices[0];
    EXPECT_NE(notices[0].find("read as written, z up"), std::string::npos) << notices[0];
    EXPECT_NE(notices[0].find(c.up_axis.find("X_UP") != std::string::npos ? "rpy=\"0 -1.5708 0\""
                                                                          : "rpy=\"1.5708 0 0\""),
              std::string::npos)
        << notices[0];
    // Once per file, however often it is loaded.
    load_mesh(file, Eigen::Vector3d(2, 2, 2), kWhere, &notices);
    EXPECT_EQ(notices.size(), 1u);
  }
}

// The shipped COLLADA mesh declares Z_UP: no notice, and it loads as it always has (a
// fuselage 12.7 m long along x, 4.6 m high along z).
TEST(MeshLoader, ShippedHelicopterIsZUp) {
  std::vector<std::string> notices;
  const TriangleMesh mesh = load_mesh(testing::project_root() + "/robots/helicopter/helicopter.dae",
                                      Eigen::Vector3d::Ones(), kWhere, &notices);
  EXPECT_TRUE(notices.empty());
  EXPECT_EQ(mesh.triangle_count(), 3620u);
  EXPECT_LT((mesh.bounds().max() - Eigen::Vector3d(6.36197, 3.97394, 2.28636)).norm(), 1e-5)
      << mesh.bounds().max().transpose();
  EXPECT_LT((mesh.bounds().min() + Eigen::Vector3d(6.36197, 3.97394, 2.28636)).norm(), 1e-5)
      << mesh.bounds().min().transpose();
}

// The notice reaches the scene's notices, which gplan prints on standard error.
TEST(MeshLoader, UpAxisNoticeReachesTheScene) {
  testing::ScratchFolder scratch;
  scratch.write("robot.dae", dae_text(test_shape()));
  const Scene scene = load_scene(scratch.write("scene.yaml", R"(name: y_up
robot: {mesh: robot.dae}
obstacles:
  - box: [0.1, 0.1, 0.1]
bounds: {min: [-1, -1, -1], max: [1, 1, 1]}
start: {base: {xyz: [-0.5, 0, 0], quat_wxyz: [1, 0, 0, 0]}}
goal: {base: {xyz: [0.5, 0, 0], quat_wxyz: [1, 0, 0, 0]}}
)"));
  ASSERT_EQ(scene.notices.size(), 1u);
  EXPECT_EQ(
      scene.notices[0].rfind(scratch.path() + "/robot.dae:3: COLLADA up axis Y_UP ignored", 0), 0u)
      << scene.notices[0];
}

// A file whose own transforms flatten its triangles (a node scaled by zero, a zero unit)
// is refused, as a zero scale is; before, it loaded as a speck nothing could touch.
// Degenerate triangles of a file as written stay: a segment still collides (the
// stability suite's degenerate robot).
TEST(MeshLoader, RejectsMeshesFlattenedByTheirOwnTransforms) {
  testing::ScratchFolder scratch;
  TriangleMesh triangle;
  triangle.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  triangle.triangles = {{0, 1, 2}};
  const std::vector<std::string> files = {
      scratch.write(
          "zero_node_scale.dae",
          dae_text(triangle, "<asset><up_axis>Z_UP</up_axis></asset>", "<scale>0 0 0</scale>")),
      scratch.write(
          "flat_node_scale.dae",
          dae_text(triangle, "<asset><up_axis>Z_UP</up_axis></asset>", "<scale>1 1 0</scale>")),
      scratch.write(
          "zero_unit.dae",
          dae_text(triangle, "<asset><unit meter=\"0\"/><up_axis>Z_UP</up_axis></asset>"))};
  for (const std::string& file : files) {
    try {
      load_mesh(file, Eigen::Vector3d::Ones(), kWhere);
      ADD_FAILURE() << file << " loaded";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("scene.yaml:7: robot.mesh: mesh '" + file + "'", 0), 0u) << message;
      EXPECT_NE(message.find("flattened by its own transforms"), std::string::npos) << message;
    }
  }
  const TriangleMesh segment =
      load_mesh(scratch.write("segment.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"),
                Eigen::Vector3d::Ones(), kWhere);
  EXPECT_EQ(segment.triangle_count(), 1u);
  // A binary STL of no triangles: assimp refuses it, and the error says what to give.
  const std::string empty = scratch.write("empty.stl", std::string(84, '\0'));
  try {
    load_mesh(empty, Eigen::Vector3d::Ones(), kWhere);
    ADD_FAILURE() << "empty.stl loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("at least one triangle"), std::string::npos) << e.what();
  }
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

// --- hostile mesh files (issue 19) ---------------------------------------------------------

std::string mesh_error(const std::string& path) {
  try {
    load_mesh(path, Eigen::Vector3d::Ones(), kWhere);
  } catch (const InputError& e) {
    return e.what();
  }
  return "loaded";
}

TEST(MeshLoader, FilesTheMeshNamesAreOpenedOnlyWhenRegular) {
  testing::ScratchFolder scratch;
  const std::string obj = std::string("mtllib parts.mtl\nusemtl red\n") + testing::kCubeObj;
  const std::string mesh = scratch.write("part.obj", obj);
  const std::string mtl = scratch.write("parts.mtl", "newmtl red\nKd 1 0 0\n");
  std::vector<std::string> files_read;
  EXPECT_EQ(load_mesh(mesh, Eigen::Vector3d::Ones(), kWhere, nullptr, &files_read)
                .triangle_count(),
            12u);
  EXPECT_NE(std::find(files_read.begin(), files_read.end(), mesh), files_read.end());
  EXPECT_EQ(files_read.size(), 2u);
  EXPECT_NE(files_read.back().find("parts.mtl"), std::string::npos);
  // The material file a FIFO: refused at once (assimp would wait for a writer forever).
  std::remove(mtl.c_str());
  ASSERT_EQ(mkfifo(mtl.c_str(), 0600), 0);
  const std::string message = mesh_error(mesh);
  EXPECT_NE(message.find("names a file that cannot be read"), std::string::npos) << message;
  EXPECT_NE(message.find("is a FIFO"), std::string::npos) << message;
  // Missing, as many downloaded OBJs' are: loaded without materials.
  std::remove(mtl.c_str());
  EXPECT_EQ(mesh_error(mesh), "loaded");
}

TEST(MeshLoader, PlyHeaderClaimingMoreThanTheFileHoldsIsRefusedBeforeReading) {
  testing::ScratchFolder scratch;
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\nproperty list uchar int "
      "vertex_indices\nend_header\n";
  const std::string message = mesh_error(scratch.write("huge.ply", header + std::string(64, '\0')));
  EXPECT_NE(message.find("claims 4000000000 vertex elements"), std::string::npos) << message;
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(mesh_error(scratch.write("small.ply", ascii)), "loaded");
}

// A COLLADA file whose nodes each hold an <instance_node> of the other.
std::string collada_with_nodes(const std::string& library_nodes) {
  return R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><up_axis>Z_UP</up_axis></asset>
  <library_nodes>)" +
         library_nodes + R"(</library_nodes>
  <library_visual_scenes><visual_scene id="s"><node id="root"><instance_node url="#a"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";
}

TEST(MeshLoader, ColladaInstanceCyclesAndExplosionsAreRefused) {
  testing::ScratchFolder scratch;
  const std::string cycle = mesh_error(scratch.write(
      "cycle.dae", collada_with_nodes(R"(<node id="a"><instance_node url="#b"/></node>
      <node id="b"><instance_node url="#a"/></node>)")));
  EXPECT_NE(cycle.find("instances itself through <instance_node> (a cycle)"), std::string::npos)
      << cycle;
  // Twenty levels each instancing the next twice: a million nodes from 2 KB.
  std::string levels;
  for (int i = 0; i < 20; ++i) {
    const std::string next = "#n" + std::to_string(i + 1);
    levels += "<node id=\"n" + std::to_string(i) + "\"><instance_node url=\"" + next +
              "\"/><instance_node url=\"" + next + "\"/></node>\n";
  }
  levels += "<node id=\"n20\"/><node id=\"a\"><instance_node url=\"#n0\"/></node>";
  const std::string explosion = mesh_error(scratch.write("explosion.dae", collada_with_nodes(levels)));
  EXPECT_NE(explosion.find("to more than 100000 nodes"), std::string::npos) << explosion;
}

}  // namespace
}  // namespace gplanner

namespace gplanner {
namespace {

// A mesh too large for the memory a run may use is refused before it is read, within a
// second, saying the estimate (issue 32: a 10-million-triangle mesh was read for 23 s
// and failed with std::bad_alloc). A binary STL says its triangle count in its header:
// the file here is sparse, 500 MB that take no disk, in an address space of 3 GB.
TEST(MeshMemory, AMeshTooLargeForMemoryIsRefusedBeforeItIsRead) {
  const testing::ScratchFolder folder;
  const std::string stl = folder.path() + "/big.stl";
  {
    std::ofstream out(stl, std::ios::binary);
    char header[84] = {};
    const std::uint32_t count = 10000000;
    std::memcpy(header + 80, &count, 4);
    out.write(header, sizeof header);
  }
  std::filesystem::resize_file(stl, 84 + 50ULL * 10000000);
  const int outcome = testing::run_with_address_space_to_spare(3ULL << 30, [&] {
    const auto start = std::chrono::steady_clock::now();
    try {
      load_mesh(stl, Eigen::Vector3d::Ones(), {"scene.yaml", 3, "robot.mesh"}, nullptr, nullptr);
    } catch (const InputError& e) {
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const std::string message = e.what();
      return seconds < 1.0 &&
             message.find("10000000 triangles) would need about") != std::string::npos &&
             message.find("simplify the mesh") != std::string::npos;
    }
    return false;
  });
  EXPECT_EQ(outcome, 0) << "refused within a second, saying the estimate";
  // An STL whose header claims more triangles than a mesh may have is refused at once.
  {
    std::fstream f(stl, std::ios::binary | std::ios::in | std::ios::out);
    const std::uint32_t count = 21000000;
    f.seekp(80);
    f.write(reinterpret_cast<const char*>(&count), 4);
  }
  std::filesystem::resize_file(stl, 84 + 50ULL * 21000000);
  try {
    load_mesh(stl, Eigen::Vector3d::Ones(), {"scene.yaml", 3, "robot.mesh"}, nullptr, nullptr);
    ADD_FAILURE() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has 21000000 triangles, more than the 20000000"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace gplanner
