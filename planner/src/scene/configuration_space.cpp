#include "gplanner/planner/scene/configuration_space.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

namespace gplanner {
namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

const char* base_type_name(BaseType type) {
  switch (type) {
    case BaseType::kFixed:
      return "fixed";
    case BaseType::kPlanar:
      return "planar";
    case BaseType::kFloating:
      return "floating";
  }
  return "unknown";
}

double wrap_angle(double angle) {
  if (angle >= -kPi && angle < kPi) return angle;  // the common case, without a division
  double wrapped = std::fmod(angle + kPi, 2 * kPi);
  if (wrapped < 0) wrapped += 2 * kPi;
  return wrapped - kPi;
}

int ConfigurationSpace::base_width() const {
  switch (base) {
    case BaseType::kFixed:
      return 0;
    case BaseType::kPlanar:
      return 3;
    case BaseType::kFloating:
      return 7;
  }
  return 0;
}

int ConfigurationSpace::position_width() const {
  return base == BaseType::kFloating ? 3 : (base == BaseType::kPlanar ? 2 : 0);
}

int ConfigurationSpace::width() const {
  return base_width() + static_cast<int>(planned_joints.size());
}

int ConfigurationSpace::dof() const {
  const int base_dof = base == BaseType::kFloating ? 6 : base_width();
  return base_dof + static_cast<int>(planned_joints.size());
}

Eigen::Isometry3d ConfigurationSpace::base_pose(const float* q) const {
  Eigen::Isometry3d X_SR = X_SB;
  if (base == BaseType::kFloating) {
    X_SR = Eigen::Isometry3d::Identity();
    X_SR.translation() = Eigen::Vector3d(q[0], q[1], q[2]);
    X_SR.linear() = Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized().toRotationMatrix();
  } else if (base == BaseType::kPlanar) {
    Eigen::Isometry3d X_BR = Eigen::Isometry3d::Identity();
    X_BR.translation() = Eigen::Vector3d(q[0], q[1], 0);
    X_BR.linear() = Eigen::AngleAxisd(q[2], Eigen::Vector3d::UnitZ()).toRotationMatrix();
    X_SR = X_SB * X_BR;
  }
  return X_SR;
}

Eigen::AlignedBox3d ConfigurationSpace::base_region() const {
  Eigen::AlignedBox3d region;
  if (base == BaseType::kFloating) {
    region.extend(base_min);
    region.extend(base_max);
  } else if (base == BaseType::kPlanar) {
    for (int corner = 0; corner < 4; ++corner) {
      const Eigen::Vector3d p_B((corner & 1) ? base_max.x() : base_min.x(),
                                (corner & 2) ? base_max.y() : base_min.y(), 0);
      region.extend(X_SB * p_B);
    }
  } else {
    region.extend(X_SB.translation());
  }
  return region;
}

void ConfigurationSpace::to_file_values(const float* q, double* values) const {
  for (int i = 0; i < width(); ++i) values[i] = q[i];
  for (int k = 0; k < position_width(); ++k) values[k] += row_origin[k];
}

void ConfigurationSpace::from_file_values(const double* values, float* q) const {
  const int positions = position_width();
  for (int i = 0; i < width(); ++i) {
    q[i] = static_cast<float>(i < positions ? values[i] - row_origin[i] : values[i]);
  }
}

void ConfigurationSpace::joint_positions(const RobotModel& robot, const float* q,
                                         double* positions) const {
  const std::size_t n = robot.joints.size();
  for (std::size_t j = 0; j < n; ++j) positions[j] = fixed_positions[j];
  const int offset = base_width();
  for (std::size_t i = 0; i < planned_joints.size(); ++i) {
    positions[planned_joints[i]] = q[offset + i];
  }
  for (std::size_t j = 0; j < n; ++j) {
    const Joint& joint = robot.joints[j];
    if (joint.mimic_joint >= 0) {
      positions[j] = joint.mimic_multiplier * positions[joint.mimic_joint] + joint.mimic_offset;
    }
  }
}

void ConfigurationSpace::sample_uniform(std::mt19937_64* rng, float* q) const {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto between = [&](double lo, double hi) { return lo + (hi - lo) * unit(*rng); };
  if (base == BaseType::kFloating) {
    for (int k = 0; k < 3; ++k) q[k] = static_cast<float>(between(base_min[k], base_max[k]));
    // Shoemake's uniform random rotation.
    const double u1 = unit(*rng), u2 = unit(*rng), u3 = unit(*rng);
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    q[3] = static_cast<float>(b * std::cos(2 * kPi * u3));
    q[4] = static_cast<float>(a * std::sin(2 * kPi * u2));
    q[5] = static_cast<float>(a * std::cos(2 * kPi * u2));
    q[6] = static_cast<float>(b * std::sin(2 * kPi * u3));
  } else if (base == BaseType::kPlanar) {
    q[0] = static_cast<float>(between(base_min[0], base_max[0]));
    q[1] = static_cast<float>(between(base_min[1], base_max[1]));
    q[2] = static_cast<float>(between(-kPi, kPi));
  }
  const int offset = base_width();
  for (std::size_t i = 0; i < planned_joints.size(); ++i) {
    q[offset + i] = static_cast<float>(between(lower[i], upper[i]));
  }
}

void ConfigurationSpace::interpolate(const float* a, const float* b, double t, float* out) const {
  auto lerp = [t](double x, double y) { return static_cast<float>(x + t * (y - x)); };
  auto short_way = [t](double x, double y) {
    return static_cast<float>(wrap_angle(x + t * wrap_angle(y - x)));
  };
  if (base == BaseType::kFloating) {
    for (int k = 0; k < 3; ++k) out[k] = lerp(a[k], b[k]);
    const Eigen::Quaterniond qa(a[3], a[4], a[5], a[6]), qb(b[3], b[4], b[5], b[6]);
    // Eigen's slerp takes the shorter arc (it flips qb when the dot product is negative).
    const Eigen::Quaterniond q = qa.normalized().slerp(t, qb.normalized());
    out[3] = static_cast<float>(q.w());
    out[4] = static_cast<float>(q.x());
    out[5] = static_cast<float>(q.y());
    out[6] = static_cast<float>(q.z());
  } else if (base == BaseType::kPlanar) {
    out[0] = lerp(a[0], b[0]);
    out[1] = lerp(a[1], b[1]);
    out[2] = short_way(a[2], b[2]);
  }
  const int offset = base_width();
  for (std::size_t i = 0; i < planned_joints.size(); ++i) {
    const int k = offset + static_cast<int>(i);
    out[k] = continuous[i] ? short_way(a[k], b[k]) : lerp(a[k], b[k]);
  }
}

std::string ConfigurationSpace::entry_name(const RobotModel& robot, int i) const {
  static const char* kFloating[] = {"x", "y", "z", "qw", "qx", "qy", "qz"};
  static const char* kPlanar[] = {"x", "y", "theta"};
  if (i < base_width()) return base == BaseType::kFloating ? kFloating[i] : kPlanar[i];
  return robot.joints[planned_joints[i - base_width()]].name;
}

std::string ConfigurationSpace::out_of_bounds(const RobotModel& robot, const float* q) const {
  const std::vector<double> row(q, q + width());
  return out_of_bounds_in_row(robot, row.data());
}

std::string ConfigurationSpace::out_of_bounds_in_file_values(const RobotModel& robot,
                                                             const double* values) const {
  // Made relative to row_origin in double, as the bounds were: rounding is monotonic, so
  // a value on a bound in the file stays on it.
  std::vector<double> row(values, values + width());
  for (int k = 0; k < position_width(); ++k) row[k] -= row_origin[k];
  return out_of_bounds_in_row(robot, row.data());
}

std::string ConfigurationSpace::out_of_bounds_in_row(const RobotModel& robot,
                                                     const double* q) const {
  std::ostringstream why;
  for (int i = 0; i < width(); ++i) {
    if (!std::isfinite(q[i])) why << entry_name(robot, i) << " is not finite; ";
  }
  // Positions as the scene file gives them; far from the origin six digits would hide
  // the difference.
  if (!row_origin.isZero()) why << std::setprecision(12);
  for (int k = 0; k < position_width(); ++k) {
    if (q[k] < base_min[k] || q[k] > base_max[k]) {
      why << entry_name(robot, k) << " = " << q[k] + row_origin[k] << " is outside the bounds ["
          << base_min[k] + row_origin[k] << ", " << base_max[k] + row_origin[k] << "]; ";
    }
  }
  why << std::setprecision(6);
  if (base == BaseType::kFloating) {
    const double norm = Eigen::Vector4d(q[3], q[4], q[5], q[6]).norm();
    if (std::abs(norm - 1) > 1e-3) why << "the quaternion has length " << norm << ", not 1; ";
  }
  const int offset = base_width();
  for (std::size_t i = 0; i < planned_joints.size(); ++i) {
    const double value = q[offset + i];
    // Continuous joints wrap; their value only has to be finite.
    if (continuous[i]) continue;
    const double slack = 1e-6 * std::max(1.0, upper[i] - lower[i]);
    if (value < lower[i] - slack || value > upper[i] + slack) {
      why << entry_name(robot, offset + static_cast<int>(i)) << " = " << value
          << " is outside its limits [" << lower[i] << ", " << upper[i] << "]; ";
    }
  }
  std::string text = why.str();
  if (text.size() >= 2) text.resize(text.size() - 2);
  return text;
}

}  // namespace gplanner
