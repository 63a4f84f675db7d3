#pragma once
// The 3-D viewer of a path (`gplan plan --html`): one self-contained HTML file that works
// offline from disk, with the obstacles as checked (triangles in the scene frame), the
// robot's links posed along the path by our forward kinematics (at every waypoint and at
// frames between them), an animation with play/pause and a slider, the start and the
// goal as ghosts, orbit and zoom. three.js (pinned in viewer/package.json) is bundled into
// the file at build time (viewer/src/viewer.js); nothing is fetched when it is viewed.
// Names from input go into the page as JSON text inside a data element, read with
// textContent: a scene named <script> runs nothing.
//
// Size: every triangle is drawn up to kViewerMaxTriangles in all (a few hundred bytes
// each: about 100 MB of HTML at the bound); beyond it each obstacle is drawn as its
// bounding box and the page and *notice say so.

#include <cstddef>
#include <string>
#include <vector>

namespace gplanner {

struct Scene;

inline constexpr std::size_t kViewerMaxTriangles = 1000000;
// Roadmap milestones drawn at most (the first ones; edges among them).
inline constexpr std::size_t kViewerMaxMilestones = 20000;

class Roadmap;

// Whether this build holds the viewer (it needs npm at build time: GPLANNER_VIEWER).
bool path_viewer_available();
// Where it does not, why and what to do (one line); "" where it does.
std::string path_viewer_missing();

// Writes the viewer of `path` (shape [waypoints, width]) atomically; summary: a line of
// text shown under the scene's name. roadmap: null, or the roadmap to draw on request
// (each milestone where the robot's last link is, or its root for a rigid body: valid
// edges green, unknown grey, invalid left out; up to kViewerMaxMilestones). *notice: ""
// or what was left out. Throws std::runtime_error where the build has no viewer.
void write_path_viewer(const std::string& file, const Scene& scene, const std::vector<float>& path,
                       const std::string& summary, std::string* notice,
                       const Roadmap* roadmap = nullptr);

// A configuration shown with what collides there highlighted (`gplan check --html`).
struct ViewedRow {
  std::string label;    // what the panel says of it (its row number and pair)
  int link = -1;        // the colliding link (robot.links index), or -1
  int obstacle = -1;    // the obstacle it meets (scene.obstacles index), or -1
  int other_link = -1;  // or the link it meets, or -1
};

// Writes the viewer of `rows` (shape [rows.size(), width]), a frame each (the slider steps
// through them, no animation), each row's link and obstacle (or second link) drawn red.
void write_rows_viewer(const std::string& file, const Scene& scene, const std::vector<float>& rows,
                       const std::vector<ViewedRow>& viewed, const std::string& summary,
                       std::string* notice);

}  // namespace gplanner
