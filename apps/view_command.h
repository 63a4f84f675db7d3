#pragma once

namespace gplan {

// gplan view PATHFILE [--scene SCENE] --html FILE
// The 3-D viewer of a path file (`gplan plan --out`, or a gplan-bench failed_paths/
// entry) in its scene: the file's `scene:` key (as written, else beside the path file),
// or --scene. Exit 0 when written, 2 on bad input.
int run_view(int argc, char** argv);

// Refuses --html (UsageError) where this gplan was built without the viewer.
void require_path_viewer();

}  // namespace gplan
