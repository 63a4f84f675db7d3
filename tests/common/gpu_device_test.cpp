// The CUDA device query: skipped where there is no device (CPU-only builds, CI).

#include "gplanner/common/gpu_device.h"

#include <gtest/gtest.h>

namespace gplanner {
namespace {

TEST(GpuDevice, ReportsTheDevice) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  EXPECT_TRUE(device.compiled_with_cuda);
  EXPECT_FALSE(device.name.empty());
  EXPECT_GE(device.compute_major, 7);
  EXPECT_GT(device.multiprocessors, 0);
  EXPECT_GT(device.memory_bytes, std::size_t(1) << 30);
  std::cout << "GPU: " << device.name << ", sm_" << device.compute_major << device.compute_minor
            << ", " << device.multiprocessors << " SMs\n";
}

TEST(CudaDevice, SaysWhyNoneIsAvailable) {
  const GpuDevice device = query_gpu_device();
  if (device.available) GTEST_SKIP() << "a GPU is present";
  EXPECT_FALSE(device.reason.empty());
}

}  // namespace
}  // namespace gplanner
