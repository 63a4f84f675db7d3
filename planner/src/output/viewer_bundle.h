#pragma once
// The 3-D viewer's script (viewer/), bundled and embedded at build time; empty where the
// build has no viewer (GPLANNER_VIEWER off).

namespace gplanner {

extern const char kViewerBundle[];

}  // namespace gplanner
