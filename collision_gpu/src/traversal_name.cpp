#include "gplanner/collision_gpu/gpu_batch_checker.h"

namespace gplanner {

const char* traversal_name(Traversal traversal) {
  switch (traversal) {
    case Traversal::kBasic:
      return "basic";
    case Traversal::kPacket:
      return "packet";
    case Traversal::kBalanced:
      return "balanced";
  }
  return "unknown";
}

bool parse_traversal(const std::string& name, Traversal* traversal) {
  for (const Traversal t : {Traversal::kBasic, Traversal::kPacket, Traversal::kBalanced}) {
    if (name == traversal_name(t)) {
      *traversal = t;
      return true;
    }
  }
  return false;
}

}  // namespace gplanner
