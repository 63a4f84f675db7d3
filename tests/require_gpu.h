#pragma once
// REQUIRE_GPU(): the first line of a GPU test (a gtest case named *Gpu*): skips it, saying
// why, where this process has no usable CUDA device; elsewhere the test runs and must use
// the GPU.

#include <gtest/gtest.h>

#include "gplanner/common/gpu_device.h"

#define REQUIRE_GPU()                                                                       \
  do {                                                                                      \
    const ::gplanner::GpuDevice gpu_for_the_test = ::gplanner::query_gpu_device();          \
    if (!gpu_for_the_test.available) GTEST_SKIP() << "no GPU: " << gpu_for_the_test.reason; \
  } while (0)
