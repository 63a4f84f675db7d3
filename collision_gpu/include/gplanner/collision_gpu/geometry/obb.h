#pragma once
// Oriented bounding boxes and their overlap test (the separating-axis test over 15
// axes, after Gottschalk, Lin and Manocha's OBBTree), with a margin so that two
// triangle sets closer than the margin always overlap.

#include "gplanner/collision_gpu/geometry/vec3.h"

namespace gplanner::geometry {

template <typename T>
struct Obb {
  Vec3<T> center;  // in the frame the box is given in
  Mat3<T> axes;    // columns are the box's unit axes in that frame
  Vec3<T> extent;  // half side lengths along the axes
};

// A box given in frame B, expressed in frame A through X_AB.
template <typename T>
GP_HD Obb<T> transformed(const Obb<T>& box_B, const Transform<T>& X_AB) {
  return {X_AB * box_B.center, X_AB.R * box_B.axes, box_B.extent};
}

// True unless a separating axis parts the boxes by more than `margin` (each box grown
// by margin / 2 on every side). Near-parallel edge axes are handled by padding |R|
// with a small epsilon, as OBBTree does, so that a degenerate cross product never
// separates falsely.
template <typename T>
GP_HD bool obbs_overlap(const Obb<T>& a, const Obb<T>& b, T margin) {
  const T kEpsilon = T(1e-6);
  const T h = margin / 2;
  const T ea[3] = {a.extent.x + h, a.extent.y + h, a.extent.z + h};
  const T eb[3] = {b.extent.x + h, b.extent.y + h, b.extent.z + h};
  // B's axes and centre in A's box frame.
  const Mat3<T> At = transpose(a.axes);
  const Mat3<T> R = At * b.axes;
  const Vec3<T> tv = At * (b.center - a.center);
  const T t[3] = {tv.x, tv.y, tv.z};
  T Rm[3][3], AbsR[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      Rm[i][j] = R.r[i][j];
      AbsR[i][j] = std::fabs(Rm[i][j]) + kEpsilon;
    }
  }
  for (int i = 0; i < 3; ++i) {  // A's axes
    const T rb = eb[0] * AbsR[i][0] + eb[1] * AbsR[i][1] + eb[2] * AbsR[i][2];
    if (std::fabs(t[i]) > ea[i] + rb) return false;
  }
  for (int j = 0; j < 3; ++j) {  // B's axes
    const T ra = ea[0] * AbsR[0][j] + ea[1] * AbsR[1][j] + ea[2] * AbsR[2][j];
    if (std::fabs(t[0] * Rm[0][j] + t[1] * Rm[1][j] + t[2] * Rm[2][j]) > ra + eb[j]) return false;
  }
  for (int i = 0; i < 3; ++i) {  // A_i x B_j
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const T ra = ea[i1] * AbsR[i2][j] + ea[i2] * AbsR[i1][j];
      const T rb = eb[j1] * AbsR[i][j2] + eb[j2] * AbsR[i][j1];
      if (std::fabs(t[i2] * Rm[i1][j] - t[i1] * Rm[i2][j]) > ra + rb) return false;
    }
  }
  return true;
}

// A sphere against a box: true unless the sphere lies farther than `margin` from it.
template <typename T>
GP_HD bool sphere_overlaps_obb(Vec3<T> center, T radius, const Obb<T>& box, T margin) {
  const Vec3<T> d = transpose(box.axes) * (center - box.center);
  T outside = 0;
  const T e[3] = {box.extent.x, box.extent.y, box.extent.z};
  for (int k = 0; k < 3; ++k) {
    const T excess = std::fabs(d[k]) - e[k];
    if (excess > 0) outside += excess * excess;
  }
  const T reach = radius + margin;
  return outside <= reach * reach;
}

}  // namespace gplanner::geometry
