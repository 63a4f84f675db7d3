#include "view_command.h"

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "command_line.h"
#include "gplanner/planner/output/output_paths.h"
#include "gplanner/planner/output/path_file.h"
#include "gplanner/planner/output/path_viewer.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/scene.h"
#include "interruption.h"

namespace gplan {

void require_path_viewer() {
  const std::string missing = gplanner::path_viewer_missing();
  if (!missing.empty()) throw UsageError("--html: " + missing);
}

int run_view(int argc, char** argv) {
  namespace fs = std::filesystem;
  const CommandLine args(argc, argv, 2, {"scene", "html"}, {});
  if (args.positionals().size() != 1)
    throw UsageError("gplan view takes one path file, not " +
                     std::to_string(args.positionals().size()) + "; give exactly one");
  if (!args.has("html")) throw UsageError("gplan view writes --html FILE; give it");
  require_path_viewer();
  const std::string path_file = args.positionals()[0];
  const std::string html = args.text("html", "");
  std::string scene_file = args.text("scene", "");
  if (scene_file.empty()) {
    // The scene as the path file names it: as written (relative to where gplan ran),
    // else beside the path file.
    scene_file = gplanner::path_file_scene(path_file);
    const fs::path beside = fs::path(path_file).parent_path() / scene_file;
    if (!fs::exists(scene_file) && fs::path(scene_file).is_relative() && fs::exists(beside))
      scene_file = beside.string();
    if (!fs::exists(scene_file)) {
      throw gplanner::InputError({path_file, 0, "scene"},
                                 "names the scene '" + scene_file +
                                     "', which is not there (neither from here nor beside "
                                     "the path file); give the scene with --scene");
    }
  }
  std::vector<gplanner::NamedFile> outputs{{"--html", html}};
  std::vector<gplanner::NamedFile> inputs{{"the path file", path_file},
                                          {"the scene file", scene_file}};
  gplanner::check_output_paths(outputs, inputs);
  const gplanner::Scene scene = gplanner::load_scene(scene_file);
  for (const std::string& notice : scene.notices)
    std::cerr << "notice: " << gplanner::terminal_text(notice) << "\n";
  for (const std::string& file : scene.input_files) inputs.push_back({"a file of the scene", file});
  gplanner::check_output_paths(outputs, inputs);
  const std::vector<float> path = gplanner::read_path_file(path_file, scene);
  if (interrupted()) return report_interruption({}, {"--html " + html});
  std::string notice;
  gplanner::write_path_viewer(
      html, scene, path,
      path_file + ": " + std::to_string(path.size() / scene.space.width()) + " waypoints", &notice);
  if (!notice.empty()) std::cerr << "notice: " << gplanner::terminal_text(notice) << "\n";
  std::cout << "wrote       --html " << gplanner::terminal_text(html) << "\n";
  return 0;
}

}  // namespace gplan
