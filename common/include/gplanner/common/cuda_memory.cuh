#pragma once
// CUDA helpers shared by the GPU code of collision_gpu and knn_gpu (CUDA translation
// units only; not installed): error checks, owning buffers that only grow, and owned
// events and streams.

#include <cuda_runtime.h>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace gplanner::cuda {

// Throws std::runtime_error "SCOPE: WHAT: the CUDA error" unless status is cudaSuccess.
inline void check(cudaError_t status, const char* scope, const char* what) {
  if (status != cudaSuccess) {
    throw std::runtime_error(std::string(scope) + ": " + what + ": " + cudaGetErrorString(status));
  }
}

// Blocks of `block` threads that cover `threads` threads (a launch's grid size).
inline int blocks_for(std::size_t threads, int block) {
  return static_cast<int>((threads + block - 1) / block);
}

// How a buffer's memory is had: on the device, or page-locked on the host (downloads
// into it run at full bus speed, where pageable memory goes through the driver's own
// staging).
struct DeviceMemory {
  static cudaError_t allocate(void** p, std::size_t bytes) { return cudaMalloc(p, bytes); }
  static void release(void* p) { cudaFree(p); }
  static constexpr const char* kAllocate = "cudaMalloc";
};
struct PinnedHostMemory {
  static cudaError_t allocate(void** p, std::size_t bytes) { return cudaMallocHost(p, bytes); }
  static void release(void* p) { cudaFreeHost(p); }
  static constexpr const char* kAllocate = "cudaMallocHost";
};

// An owning buffer of T that only grows; kernels only ever see the raw pointer.
template <typename T, typename Memory>
class GrowingBuffer {
 public:
  GrowingBuffer() = default;
  ~GrowingBuffer() { release(); }
  GrowingBuffer(const GrowingBuffer&) = delete;
  GrowingBuffer& operator=(const GrowingBuffer&) = delete;

  void reserve(std::size_t count) {
    if (count <= capacity_) return;
    release();
    check(Memory::allocate(reinterpret_cast<void**>(&data_),
                           std::max<std::size_t>(count, 1) * sizeof(T)),
          "CUDA", Memory::kAllocate);
    capacity_ = count;
  }
  // Copies `host` to the start of the (device) buffer, growing it as needed.
  void upload(const std::vector<T>& host) {
    reserve(host.size());
    if (!host.empty()) {
      check(cudaMemcpy(data_, host.data(), host.size() * sizeof(T), cudaMemcpyHostToDevice), "CUDA",
            "upload");
    }
  }
  T* get() const { return data_; }
  std::size_t capacity() const { return capacity_; }

 private:
  void release() {
    if (data_) Memory::release(data_);
    data_ = nullptr;
    capacity_ = 0;
  }
  T* data_ = nullptr;
  std::size_t capacity_ = 0;
};

// An owned CUDA handle (an event, a stream), destroyed with its owner.
template <typename Handle, cudaError_t (*Destroy)(Handle)>
class OwnedHandle {
 public:
  OwnedHandle() = default;
  ~OwnedHandle() {
    if (handle_) Destroy(handle_);
  }
  OwnedHandle(const OwnedHandle&) = delete;
  OwnedHandle& operator=(const OwnedHandle&) = delete;
  Handle get() const { return handle_; }

 protected:
  Handle handle_ = nullptr;
};

// A CUDA event (timing by default), made on construction.
class Event : public OwnedHandle<cudaEvent_t, cudaEventDestroy> {
 public:
  explicit Event(unsigned flags = cudaEventDefault) {
    check(cudaEventCreateWithFlags(&handle_, flags), "CUDA", "cudaEventCreate");
  }
};

// A CUDA stream (non-blocking: it does not wait for the default stream), made on
// construction.
class Stream : public OwnedHandle<cudaStream_t, cudaStreamDestroy> {
 public:
  explicit Stream(unsigned flags = cudaStreamNonBlocking) {
    check(cudaStreamCreateWithFlags(&handle_, flags), "CUDA", "cudaStreamCreate");
  }
};

template <typename T>
using DeviceBuffer = GrowingBuffer<T, DeviceMemory>;
template <typename T>
using PinnedBuffer = GrowingBuffer<T, PinnedHostMemory>;

}  // namespace gplanner::cuda
