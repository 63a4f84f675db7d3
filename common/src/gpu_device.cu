#include "gplanner/common/gpu_device.h"

#include <cuda_runtime.h>

#include <stdexcept>

namespace gplanner {

int gpu_device_count(std::string* reason) {
  int count = 0;
  const cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess) {
    if (reason) *reason = cudaGetErrorString(status);
    return 0;
  }
  if (count == 0 && reason) *reason = "no CUDA device found";
  return count;
}

GpuDevice query_gpu_device(int index) {
  GpuDevice device;
  device.compiled_with_cuda = true;
  device.index = index;
  device.count = gpu_device_count(&device.reason);
  if (device.count == 0) return device;
  if (index < 0 || index >= device.count) {
    device.reason = "device " + std::to_string(index) + " asked for; this process sees " +
                    std::to_string(device.count) + " CUDA device" +
                    (device.count > 1 ? "s, 0 to " + std::to_string(device.count - 1) : ", 0") +
                    " (CUDA_VISIBLE_DEVICES chooses which)";
    return device;
  }
  cudaDeviceProp properties{};
  const cudaError_t props_status = cudaGetDeviceProperties(&properties, index);
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

GpuDeviceScope::GpuDeviceScope(int index) {
  int current = 0;
  cudaError_t status = cudaGetDevice(&current);
  if (status == cudaSuccess && current == index) return;
  if (status == cudaSuccess) status = cudaSetDevice(index);
  if (status != cudaSuccess) {
    throw std::runtime_error("CUDA device " + std::to_string(index) +
                             " cannot be used: " + cudaGetErrorString(status));
  }
  previous_ = current;
}

GpuDeviceScope::~GpuDeviceScope() {
  if (previous_ >= 0) cudaSetDevice(previous_);  // a destructor reports nothing
}

}  // namespace gplanner
