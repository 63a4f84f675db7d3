#include "gplanner/planner/output/path_picture.h"

#include <algorithm>
#include <cmath>
#include <iomanip>

#include "gplanner/planner/output/atomic_file.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/scene/forward_kinematics.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {
namespace {

using Point = Eigen::Vector2d;

// Convex hull (Andrew's monotone chain), counter-clockwise.
std::vector<Point> convex_hull(std::vector<Point> points) {
  std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (points.size() < 3) return points;
  auto cross = [](const Point& o, const Point& a, const Point& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Point> hull(2 * points.size());
  std::size_t k = 0;
  for (const Point& p : points) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

}  // namespace

void write_path_picture(const std::string& file, const Scene& scene,
                        const std::vector<float>& path) {
  const ConfigurationSpace& space = scene.space;
  const RobotModel& robot = scene.robot;
  const int width = space.width();
  const std::size_t m = path.size() / width;
  // Drawn in the scene frame (obstacles and poses alike), relative to its bounds. The
  // view: the two axes along which the scene extends most.
  const Eigen::AlignedBox3d bounds = scene.bounds_S();
  const Eigen::Vector3d size = bounds.sizes();
  int drop = 0;
  for (int a = 1; a < 3; ++a)
    if (size[a] < size[drop]) drop = a;
  const int u = drop == 0 ? 1 : 0, v = drop == 2 ? 1 : 2;
  const double scale = 1000.0 / std::max(size[u], size[v]);
  const double w_px = size[u] * scale, h_px = size[v] * scale;
  auto px = [&](const Eigen::Vector3d& p) {
    return Point((p[u] - bounds.min()[u]) * scale, h_px - (p[v] - bounds.min()[v]) * scale);
  };
  auto polygon = [](std::ostream& out, const std::vector<Point>& points, const char* style) {
    out << "<polygon points=\"";
    for (const Point& p : points) out << p.x() << ',' << p.y() << ' ';
    out << "\" " << style << "/>\n";
  };

  write_file_atomically(file, [&](std::ostream& out) {
    out << std::fixed << std::setprecision(1);
    out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w_px + 20 << "\" height=\""
        << h_px + 40 << "\" viewBox=\"-10 -30 " << w_px + 20 << ' ' << h_px + 40 << "\">\n"
        << "<rect x=\"-10\" y=\"-30\" width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        << "<text x=\"0\" y=\"-12\" font-family=\"sans-serif\" font-size=\"14\">"
        << xml_escaped(scene.name) << ": " << m << " waypoints; view along "
        << "xyz"[drop] << " (obstacles grey, darker where they overlap)</text>\n";
    // Obstacles, triangle by triangle (walls seen edge-on show as lines), leaving out
    // those covering a tenth of the picture or more (floors and ceilings, which would
    // hide everything under one shade).
    out << "<g fill=\"#444\" fill-opacity=\"0.12\" stroke=\"#444\" stroke-opacity=\"0.35\" "
           "stroke-width=\"0.6\">\n";
    for (const Obstacle& obstacle : scene.obstacles) {
      const TriangleMesh& mesh = obstacle.mesh_S;
      for (const Eigen::Vector3i& t : mesh.triangles) {
        const Point a = px(mesh.vertices[t[0]]), b = px(mesh.vertices[t[1]]),
                    c = px(mesh.vertices[t[2]]);
        const double area = std::fabs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x()) / 2;
        if (area < 0.1 * w_px * h_px) polygon(out, {a, b, c}, "");
      }
    }
    out << "</g>\n";
    // The robot at up to 24 waypoints spread along the path: each link's outline.
    std::vector<double> positions(robot.joints.size());
    std::vector<Eigen::Isometry3d> X_WL;
    const std::size_t shown = std::min<std::size_t>(m, 24);
    for (std::size_t s = 0; s < shown; ++s) {
      const std::size_t i = shown == 1 ? 0 : s * (m - 1) / (shown - 1);
      const float* q = &path[i * width];
      space.joint_positions(robot, q, positions.data());
      forward_kinematics(robot, space.base_pose(q), positions.data(), &X_WL);
      const char* style = i == 0       ? "fill=\"#2a2\" fill-opacity=\"0.35\" stroke=\"#060\""
                          : i == m - 1 ? "fill=\"#d22\" fill-opacity=\"0.35\" stroke=\"#800\""
                                       : "fill=\"#36c\" fill-opacity=\"0.15\" stroke=\"#236\"";
      for (std::size_t l = 0; l < robot.links.size(); ++l) {
        std::vector<Point> points;
        for (const Eigen::Vector3d& p : robot.links[l].collision.vertices)
          points.push_back(px(X_WL[l] * p));
        if (points.size() >= 3) polygon(out, convex_hull(points), style);
      }
    }
    // The root's path.
    out << "<polyline fill=\"none\" stroke=\"#c60\" stroke-width=\"2\" points=\"";
    for (std::size_t i = 0; i < m; ++i) {
      const Point p = px(space.base_pose(&path[i * width]).translation());
      out << p.x() << ',' << p.y() << ' ';
    }
    out << "\"/>\n</svg>\n";
  });
}

}  // namespace gplanner
