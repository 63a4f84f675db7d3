#include "gplanner/planner/output/path_viewer.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <stdexcept>

#include "gplanner/planner/output/atomic_file.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/planning/roadmap.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/forward_kinematics.h"
#include "gplanner/planner/scene/scene.h"
#include "viewer_bundle.h"

namespace gplanner {
namespace {

// Frames of the animation besides the waypoints, spread by the segments' lengths.
constexpr int kFrames = 300;

// JSON text safe inside a <script> element: every '<' (only ever inside strings) written
// as \u003c, so that nothing in it can end or comment out the element.
std::string script_safe(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (std::size_t i = 0; i < json.size(); ++i) {
    if (json[i] == '<') {
      out += "\\u003c";
    } else {
      out += json[i];
    }
  }
  return out;
}

void write_mesh(std::ostream& out, const TriangleMesh& mesh) {
  out << "{\"positions\":[";
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Eigen::Vector3d& p = mesh.vertices[v];
    out << (v ? "," : "") << p.x() << ',' << p.y() << ',' << p.z();
  }
  out << "],\"indices\":[";
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3i& i = mesh.triangles[t];
    out << (t ? "," : "") << i[0] << ',' << i[1] << ',' << i[2];
  }
  out << "]}";
}

TriangleMesh box_mesh(const TriangleMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : mesh.vertices) box.extend(p);
  TriangleMesh out;
  for (int c = 0; c < 8; ++c)
    out.vertices.push_back(box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)));
  // Corners: bit 0 x, bit 1 y, bit 2 z.
  const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                            {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& f : faces) out.triangles.emplace_back(f[0], f[1], f[2]);
  return out;
}

}  // namespace

bool path_viewer_available() { return kViewerBundle[0] != '\0'; }

std::string path_viewer_missing() {
  return path_viewer_available()
             ? ""
             : "this gplan was built without the viewer (no npm at build time); build with "
               "-DGPLANNER_VIEWER=ON where npm can reach its registry";
}

namespace {

// The page: `frames` (shape [*, width]) are the robot's configurations in order;
// waypoint_frames the frames that are waypoints (the slider names them); viewed (empty, or
// one per frame) what to highlight and say per frame; roadmap drawn where given.
void write_viewer(const std::string& file, const Scene& scene, const std::vector<float>& frames,
                  const std::vector<std::size_t>& waypoint_frames,
                  const std::vector<ViewedRow>& viewed, const std::string& summary,
                  std::string* notice, const Roadmap* roadmap) {
  if (!path_viewer_available()) throw std::runtime_error(path_viewer_missing());
  const ConfigurationSpace& space = scene.space;
  const RobotModel& robot = scene.robot;
  const int width = space.width();
  notice->clear();
  std::size_t triangles = 0;
  for (const Link& link : robot.links) triangles += link.collision.triangle_count();
  for (const Obstacle& o : scene.obstacles) triangles += o.mesh_S.triangle_count();
  const bool boxes = triangles > kViewerMaxTriangles;
  if (boxes) {
    *notice = std::to_string(triangles) + " triangles are more than the viewer draws (" +
              std::to_string(kViewerMaxTriangles) + "): each obstacle is drawn as its bounding box";
  }
  write_file_atomically(file, [&](std::ostream& out) {
    out << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
        << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
        << "<title>gplan: " << xml_escaped(scene.name) << "</title>\n"
        << "<style>html,body{margin:0;height:100%;overflow:hidden;font-family:sans-serif}"
           "canvas{display:block}#panel{position:absolute;top:8px;left:8px;padding:8px 10px;"
           "background:rgba(255,255,255,.85);border-radius:6px;font-size:13px;max-width:60%}"
           "#panel .title{font-weight:bold;font-size:15px}#panel .notice{color:#a40}"
           "#panel .legend{color:#555}#panel input[type=range]{width:260px;vertical-align:middle}"
           "</style>\n</head><body data-status=\"loading\">\n"
        << "<script type=\"application/json\" id=\"gplan-data\">";
    std::ostringstream json;
    json << std::setprecision(7);
    json << "{\"name\":" << json_string(scene.name) << ",\"summary\":" << json_string(summary)
         << ",\"notice\":" << json_string(*notice) << ",\"meshes\":[";
    int meshes = 0;
    std::vector<int> link_mesh(robot.links.size(), -1);
    for (std::size_t l = 0; l < robot.links.size(); ++l) {
      if (robot.links[l].collision.empty()) continue;
      json << (meshes ? "," : "");
      write_mesh(json, robot.links[l].collision);
      link_mesh[l] = meshes++;
    }
    std::vector<int> obstacle_mesh;
    for (const Obstacle& o : scene.obstacles) {
      json << (meshes ? "," : "");
      write_mesh(json, boxes ? box_mesh(o.mesh_S) : o.mesh_S);
      obstacle_mesh.push_back(meshes++);
    }
    json << "],\"obstacles\":[";
    for (std::size_t i = 0; i < scene.obstacles.size(); ++i) {
      json << (i ? "," : "") << "{\"name\":" << json_string(scene.obstacles[i].name)
           << ",\"mesh\":" << obstacle_mesh[i] << "}";
    }
    json << "],\"links\":[";
    for (std::size_t l = 0; l < robot.links.size(); ++l) {
      json << (l ? "," : "") << "{\"name\":" << json_string(robot.links[l].name)
           << ",\"mesh\":" << link_mesh[l] << "}";
    }
    json << "],\"frames\":[";
    std::vector<double> positions(robot.joints.size());
    std::vector<Eigen::Isometry3d> X_SL;
    json << std::setprecision(6);
    for (std::size_t f = 0; f < frames.size() / width; ++f) {
      const float* c = &frames[f * width];
      space.joint_positions(robot, c, positions.data());
      forward_kinematics(robot, space.base_pose(c), positions.data(), &X_SL);
      json << (f ? ",[" : "[");
      for (std::size_t l = 0; l < X_SL.size(); ++l) {
        const Eigen::Matrix3d r = X_SL[l].linear();
        const Eigen::Vector3d t = X_SL[l].translation();
        for (int k = 0; k < 9; ++k) json << (l || k ? "," : "") << r(k % 3, k / 3);
        json << ',' << t.x() << ',' << t.y() << ',' << t.z();
      }
      json << "]";
    }
    json << "],\"waypoints\":[";
    for (std::size_t i = 0; i < waypoint_frames.size(); ++i)
      json << (i ? "," : "") << waypoint_frames[i];
    json << "]";
    if (!viewed.empty()) {
      json << ",\"rows\":[";
      for (std::size_t f = 0; f < viewed.size(); ++f) {
        const ViewedRow& v = viewed[f];
        json << (f ? "," : "") << "{\"label\":" << json_string(v.label) << ",\"link\":" << v.link
             << ",\"obstacle\":" << v.obstacle << ",\"other_link\":" << v.other_link << "}";
      }
      json << "]";
    }
    if (roadmap != nullptr) {
      // Each milestone where the last link is (its origin), the root for a rigid body.
      const std::size_t n = std::min(roadmap->vertex_count(), kViewerMaxMilestones);
      json << ",\"roadmap\":{\"milestones\":" << roadmap->vertex_count() << ",\"points\":[";
      for (std::size_t v = 0; v < n; ++v) {
        const float* c = roadmap->vertex(v);
        space.joint_positions(robot, c, positions.data());
        forward_kinematics(robot, space.base_pose(c), positions.data(), &X_SL);
        const Eigen::Vector3d p = X_SL.back().translation();
        json << (v ? "," : "") << p.x() << ',' << p.y() << ',' << p.z();
      }
      for (const EdgeState state : {EdgeState::kValid, EdgeState::kUnknown}) {
        json << (state == EdgeState::kValid ? "],\"valid\":[" : "],\"unknown\":[");
        bool first = true;
        for (const RoadmapEdge& e : roadmap->edges()) {
          if (e.state != state || e.a >= n || e.b >= n) continue;
          json << (first ? "" : ",") << e.a << ',' << e.b;
          first = false;
        }
      }
      json << "]}";
    }
    json << "}";
    out << script_safe(json.str()) << "</script>\n<script>" << kViewerBundle
        << "</script>\n</body></html>\n";
  });
}

}  // namespace

void write_path_viewer(const std::string& file, const Scene& scene, const std::vector<float>& path,
                       const std::string& summary, std::string* notice, const Roadmap* roadmap) {
  const ConfigurationSpace& space = scene.space;
  const int width = space.width();
  const std::size_t m = path.size() / width;
  // Frames: every waypoint, and frames between them by the segments' lengths.
  const ConfigurationMetric metric = make_metric(space, scene.planner);
  std::vector<double> lengths(m > 0 ? m - 1 : 0);
  double total = 0;
  for (std::size_t i = 0; i + 1 < m; ++i)
    total += lengths[i] = distance(metric, &path[i * width], &path[(i + 1) * width]);
  std::vector<float> frames;
  std::vector<std::size_t> waypoint_frames;
  std::vector<float> q(width);
  for (std::size_t i = 0; i < m; ++i) {
    waypoint_frames.push_back(frames.size() / width);
    frames.insert(frames.end(), &path[i * width], &path[(i + 1) * width]);
    if (i + 1 == m) break;
    const int between = total > 0 ? static_cast<int>(std::lround(kFrames * lengths[i] / total)) : 0;
    for (int j = 1; j < between; ++j) {
      space.interpolate(&path[i * width], &path[(i + 1) * width], double(j) / between, q.data());
      frames.insert(frames.end(), q.begin(), q.end());
    }
  }
  write_viewer(file, scene, frames, waypoint_frames, {}, summary, notice, roadmap);
}

void write_rows_viewer(const std::string& file, const Scene& scene, const std::vector<float>& rows,
                       const std::vector<ViewedRow>& viewed, const std::string& summary,
                       std::string* notice) {
  std::vector<std::size_t> waypoint_frames(viewed.size());
  for (std::size_t i = 0; i < viewed.size(); ++i) waypoint_frames[i] = i;
  write_viewer(file, scene, rows, waypoint_frames, viewed, summary, notice, nullptr);
}

}  // namespace gplanner
