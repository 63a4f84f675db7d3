#pragma once
// What the fuzz targets do with one input, shared by the libFuzzer programs
// (tests/fuzz/*_fuzzer.cpp, built with -DGPLANNER_FUZZ=ON and clang) and the corpus
// replay test that CI runs. Each returns normally for any input: bad input must end in
// an InputError (caught here); anything else (another exception, a crash, a broken
// invariant, a sanitizer report) is a finding.

#include <cstddef>
#include <cstdint>

namespace gplanner::fuzz {

// The bytes as a scene file (beside a small mesh and a URDF robot it may name).
void scene_file(const std::uint8_t* data, std::size_t size);
// The bytes as a URDF file (beside a small mesh it may name).
void urdf_file(const std::uint8_t* data, std::size_t size);
// The bytes as an SRDF file applied to a small valid robot.
void srdf_file(const std::uint8_t* data, std::size_t size);
// The bytes as a triangle soup (vertex count, then raw float coordinates, then raw
// vertex indices) handed to mesh validation and, when it passes, the BVH builder,
// whose result is checked: every triangle in one leaf, every box holding its
// triangles.
void triangle_soup(const std::uint8_t* data, std::size_t size);

// The bytes as gplan's command line: split into arguments at NUL bytes (the first the
// command) and run through gplan's own command code (apps/gplan_commands.h) in the
// fuzz folder, beside a small scene (scene.yaml: a cube among boxes; arm.yaml: a
// two-joint arm) and a valid roadmap for it (map.roadmap). gplan plan gets
// --time-limit 0.05; inputs that name a path with '/' (anything outside the folder,
// /dev/null among them), set the time limit themselves or ask for an in-range but
// slow count (--n, --repeat, --milestones above 1000, --threads above 64, up to
// twelve digits) are skipped. Usage and input errors (exit 2) are normal ends.
void command_line(const std::uint8_t* data, std::size_t size);
// The bytes after the first as a roadmap file for the small scene (load_roadmap); when
// the first byte is odd, the checksum at the end is first made right (the fuzzer
// cannot forge it), so that what lies behind it is fuzzed too. A roadmap that loads
// must hold its invariants: the scene's width, every vertex finite within bounds and
// limits, every edge between two distinct existing vertices with a finite
// non-negative length and a known state.
void roadmap_file(const std::uint8_t* data, std::size_t size);

}  // namespace gplanner::fuzz
