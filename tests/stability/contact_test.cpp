// Stability: contacts whose distance is known by construction (a cube robot against a
// cube obstacle, face to face, edge to edge and vertex to face), from deep penetration
// to separations far beyond the tolerance band, at model sizes from 0.1 mm to 10 km;
// every backend judged against the band: penetration must collide, a distance above
// delta must be free, in between either. The *Gpu* case runs the same on the GPU.

#include <gtest/gtest.h>

#include "contact_cases.h"
#include "gplanner/common/gpu_device.h"

namespace gplanner {
namespace {

using testing::expect_contacts_within_band;

const std::vector<double> kSides = {1e-4, 1e-2, 1.0, 1e2, 1e4};

void expect_within_band(const std::vector<std::string>& backends) {
  expect_contacts_within_band(backends, kSides);
}

TEST(StabilityContacts, CpuAndFclKeepTheBand) { expect_within_band({"cpu", "fcl"}); }

TEST(StabilityContacts, GpuKeepsTheBand) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  expect_within_band({"gpu"});
}

}  // namespace
}  // namespace gplanner
