#include "gplanner/common/gpu_device.h"

#include <cuda_runtime.h>

namespace gplanner {

GpuDevice query_gpu_device() {
  GpuDevice device;
  device.compiled_with_cuda = true;
  int count = 0;
  const cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess) {
    device.reason = cudaGetErrorString(status);
    return device;
  }
  if (count == 0) {
    device.reason = "no CUDA device found";
    return device;
  }
  cudaDeviceProp properties{};
  const cudaError_t props_status = cudaGetDeviceProperties(&properties, 0);
  if (props_status != cudaSuccess) {
    device.reason = cudaGetErrorString(props_status);
    return device;
  }
  device.available = true;
  device.name = properties.name;
  device.compute_major = properties.major;
  device.compute_minor = properties.minor;
  device.multiprocessors = properties.multiProcessorCount;
  device.memory_bytes = properties.totalGlobalMem;
  return device;
}

}  // namespace gplanner
