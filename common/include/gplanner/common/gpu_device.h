#pragma once
// Which CUDA devices, if any, this process can use, and choosing one for a thread. Plain
// C++: no CUDA headers.
//
// Devices are numbered as the CUDA runtime numbers them: the ones CUDA_VISIBLE_DEVICES
// leaves visible, from 0.

#include <cstddef>
#include <string>

namespace gplanner {

struct GpuDevice {
  bool available = false;  // a CUDA device exists and the runtime initialised
  bool compiled_with_cuda = false;
  int index = 0;     // the device asked for
  int count = 0;     // devices this process sees
  std::string name;  // e.g. "NVIDIA H100 80GB HBM3"
  int compute_major = 0;
  int compute_minor = 0;
  int multiprocessors = 0;
  std::size_t memory_bytes = 0;
  std::string reason;  // why no device is available, when none is
};

// Queries device `index` (not available, with a reason, where the process sees fewer
// devices). Initialises the CUDA runtime: call it only when a GPU backend is wanted,
// never for the fcl backend.
GpuDevice query_gpu_device(int index = 0);

// The number of CUDA devices this process sees: 0 where there are none, or no driver, or
// gplanner was built without CUDA (`reason`, when given, then says why). Initialises the
// CUDA runtime, as query_gpu_device does.
int gpu_device_count(std::string* reason = nullptr);

// Makes `index` the calling thread's current CUDA device while it lives, then the one
// before it again. Every GPU object of gplanner that is given a device makes, uses and
// frees its memory under one of these, so that objects on different devices can be used
// from one thread. Without CUDA it does nothing.
class GpuDeviceScope {
 public:
  explicit GpuDeviceScope(int index);
  ~GpuDeviceScope();
  GpuDeviceScope(const GpuDeviceScope&) = delete;
  GpuDeviceScope& operator=(const GpuDeviceScope&) = delete;

 private:
  int previous_ = -1;  // -1: nothing to set back
};

}  // namespace gplanner
