#include "traversals/basic.cuh"

namespace gplanner::traversals {
namespace {

__global__ void basic_kernel(CollisionModelView m, const float* d_q, int n,
                             std::uint8_t* d_verdicts, DeviceTestCounts* d_counts) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  detail::TraversalCounts counts;
  if (i < n) {
    detail::Xf X_WL[detail::kMaxLinks];
    const float* q = d_q + static_cast<std::size_t>(i) * m.width;
    d_verdicts[i] = detail::query_collides(m, q, query_clearances(m, i), X_WL, &counts) ? 1 : 0;
  }
  add_counts(counts, d_counts);
}

}  // namespace

void run_basic(const CollisionModelView& m, const float* d_q, int n, std::uint8_t* d_verdicts,
               DeviceTestCounts* d_counts) {
  basic_kernel<<<blocks_for(n, 128), 128>>>(m, d_q, n, d_verdicts, d_counts);
  check_cuda(cudaGetLastError(), "basic kernel");
}

}  // namespace gplanner::traversals
