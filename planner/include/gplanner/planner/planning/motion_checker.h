#pragma once
// What checks straight-line motions for a planner: at samples (LocalPlanner) or
// certified free along the whole motion (CertifiedMotions).

#include <cstddef>
#include <cstdint>

namespace gplanner {

class MotionChecker {
 public:
  virtual ~MotionChecker() = default;
  // from, to: shape [count, width]; invalid: shape [count], 1 for a motion found not
  // free. Returns false, with `invalid` incomplete, when the checker's stop condition
  // said to stop part way.
  virtual bool check_motions(const float* from, const float* to, std::size_t count,
                             std::uint8_t* invalid) = 0;
};

}  // namespace gplanner
