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

}  // namespace gplanner::fuzz
