#include "gplanner/planner/scene/straight_line.h"

namespace gplanner {

void StraightLine::reset(const ConfigurationSpace& space, const float* a, const float* b) {
  const int width = space.width();
  from_.resize(width);
  delta_.resize(width);
  wrapped_.clear();
  for (int k = 0; k < width; ++k) {
    from_[k] = a[k];
    delta_[k] = static_cast<double>(b[k]) - static_cast<double>(a[k]);
  }
  floating_ = space.base == BaseType::kFloating;
  if (floating_) {
    qa_ = Eigen::Quaterniond(a[3], a[4], a[5], a[6]).normalized();
    qb_ = Eigen::Quaterniond(b[3], b[4], b[5], b[6]).normalized();
  } else if (space.base == BaseType::kPlanar) {
    delta_[2] = wrap_angle(delta_[2]);
    wrapped_.push_back(2);
  }
  const int offset = space.base_width();
  for (std::size_t i = 0; i < space.planned_joints.size(); ++i) {
    if (!space.continuous[i]) continue;
    const int k = offset + static_cast<int>(i);
    delta_[k] = wrap_angle(delta_[k]);
    wrapped_.push_back(k);
  }
}

void StraightLine::at(double t, float* out) const {
  const int width = static_cast<int>(from_.size());
  const double* from = from_.data();
  const double* delta = delta_.data();
  for (int k = 0; k < width; ++k) out[k] = static_cast<float>(from[k] + t * delta[k]);
  for (const int k : wrapped_) out[k] = static_cast<float>(wrap_angle(from[k] + t * delta[k]));
  if (floating_) {
    // Eigen's slerp takes the shorter arc, as interpolate's does.
    const Eigen::Quaterniond q = qa_.slerp(t, qb_);
    out[3] = static_cast<float>(q.w());
    out[4] = static_cast<float>(q.x());
    out[5] = static_cast<float>(q.y());
    out[6] = static_cast<float>(q.z());
  }
}

}  // namespace gplanner
