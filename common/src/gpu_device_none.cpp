#include "gplanner/common/gpu_device.h"

namespace gplanner {

namespace {
constexpr const char* kNoCuda = "gplanner was built without CUDA";
}

GpuDevice query_gpu_device(int index) {
  GpuDevice device;
  device.index = index;
  device.reason = kNoCuda;
  return device;
}

int gpu_device_count(std::string* reason) {
  if (reason) *reason = kNoCuda;
  return 0;
}

GpuDeviceScope::GpuDeviceScope(int) {}
GpuDeviceScope::~GpuDeviceScope() = default;

}  // namespace gplanner
