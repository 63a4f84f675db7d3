#include "gplanner/common/gpu_device.h"

namespace gplanner {

GpuDevice query_gpu_device() {
  GpuDevice device;
  device.reason = "gplanner was built without CUDA";
  return device;
}

}  // namespace gplanner
