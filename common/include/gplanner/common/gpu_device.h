#pragma once
// Which CUDA device, if any, this process can use. Plain C++: no CUDA headers.

#include <cstddef>
#include <string>

namespace gplanner {

struct GpuDevice {
  bool available = false;  // a CUDA device exists and the runtime initialised
  bool compiled_with_cuda = false;
  std::string name;  // e.g. "NVIDIA H100 80GB HBM3"
  int compute_major = 0;
  int compute_minor = 0;
  int multiprocessors = 0;
  std::size_t memory_bytes = 0;
  std::string reason;  // why no device is available, when none is
};

// Queries device 0. Initialises the CUDA runtime: call it only when a GPU backend
// is wanted, never for the fcl backend.
GpuDevice query_gpu_device();

}  // namespace gplanner
