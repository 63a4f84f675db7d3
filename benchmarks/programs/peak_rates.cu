// Peak rates of the collision core's two unit tests on this GPU: how many BV-pair
// tests and triangle tests per second the hardware sustains when nothing else gets in
// the way (operands in registers and L1, no divergence, no traversal). Multiplying a
// traversal's test counts by these rates gives the time the same work would take at
// the physical limit, to set beside the measured time.
//
// usage: gplanner_peak_rates

#include <cuda_runtime.h>

#include <cstdio>
#include <random>
#include <vector>

#include "gplanner/collision_gpu/detail/query.h"

namespace {

using namespace gplanner;

constexpr int kPool = 64;      // distinct nodes / triangles in the pool (cache resident)
constexpr int kRepeats = 256;  // tests per thread

__global__ void bv_kernel(const BvhNode* d_nodes, const detail::Xf* d_poses, int* d_hits) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  const detail::Xf X = d_poses[t % kPool];
  int hits = 0;
  for (int r = 0; r < kRepeats; ++r) {
    hits +=
        detail::nodes_overlap(d_nodes[(t + r) % kPool], d_nodes[(t * 7 + 3 * r) % kPool], X, 1e-4f);
  }
  d_hits[t] = hits;
}

__global__ void triangle_kernel(const BvhTriangle* d_triangles, const detail::Xf* d_poses,
                                int* d_hits) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  const detail::Xf X = d_poses[t % kPool];
  int hits = 0;
  for (int r = 0; r < kRepeats; ++r) {
    hits += detail::leaf_collides(d_triangles[(t + r) % kPool],
                                  d_triangles[(t * 7 + 3 * r) % kPool], X, 1e-4f);
  }
  d_hits[t] = hits;
}

template <typename Kernel, typename Data>
double rate(Kernel kernel, const Data* d_data, const detail::Xf* d_poses, int* d_hits,
            int threads) {
  const int block = 256, grid = threads / block;
  kernel<<<grid, block>>>(d_data, d_poses, d_hits);  // warm-up
  cudaEvent_t start, stop;
  cudaEventCreate(&start);
  cudaEventCreate(&stop);
  cudaEventRecord(start);
  const int launches = 10;
  for (int i = 0; i < launches; ++i) kernel<<<grid, block>>>(d_data, d_poses, d_hits);
  cudaEventRecord(stop);
  cudaEventSynchronize(stop);
  float ms = 0;
  cudaEventElapsedTime(&ms, start, stop);
  return double(threads) * kRepeats * launches / (ms * 1e-3);
}

}  // namespace

int main() {
  cudaDeviceProp properties{};
  if (cudaGetDeviceProperties(&properties, 0) != cudaSuccess) {
    std::fprintf(stderr, "gplanner_peak_rates: no CUDA device\n");
    return 1;
  }
  // A pool of nearby boxes and triangles (about half the pairs overlap), random poses.
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f), e(0.1f, 0.4f);
  std::vector<BvhNode> nodes(kPool);
  std::vector<BvhTriangle> triangles(kPool);
  std::vector<detail::Xf> poses(kPool);
  for (int i = 0; i < kPool; ++i) {
    const geometry::Mat3<float> R =
        geometry::axis_angle(geometry::Vec3<float>{0.6f, 0.0f, 0.8f}, u(rng) * 6);
    BvhNode& n = nodes[i];
    for (int k = 0; k < 3; ++k) {
      n.center[k] = u(rng);
      n.extent[k] = e(rng);
      for (int c = 0; c < 3; ++c) n.axes[3 * k + c] = R.r[k][c];
    }
    n.radius = std::sqrt(n.extent[0] * n.extent[0] + n.extent[1] * n.extent[1] +
                         n.extent[2] * n.extent[2]);
    n.child = 0;
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < 3; ++c) triangles[i].v[k][c] = u(rng);
      triangles[i].v[k][3] = 0;
    }
    poses[i] = {geometry::axis_angle(geometry::Vec3<float>{0.0f, 1.0f, 0.0f}, u(rng)),
                {u(rng), u(rng), u(rng)}};
  }
  BvhNode* d_nodes;
  BvhTriangle* d_triangles;
  detail::Xf* d_poses;
  int* d_hits;
  const int threads = properties.multiProcessorCount * 2048;
  cudaMalloc(&d_nodes, sizeof(BvhNode) * kPool);
  cudaMalloc(&d_triangles, sizeof(BvhTriangle) * kPool);
  cudaMalloc(&d_poses, sizeof(detail::Xf) * kPool);
  cudaMalloc(&d_hits, sizeof(int) * threads);
  cudaMemcpy(d_nodes, nodes.data(), sizeof(BvhNode) * kPool, cudaMemcpyHostToDevice);
  cudaMemcpy(d_triangles, triangles.data(), sizeof(BvhTriangle) * kPool, cudaMemcpyHostToDevice);
  cudaMemcpy(d_poses, poses.data(), sizeof(detail::Xf) * kPool, cudaMemcpyHostToDevice);
  const double bv = rate(bv_kernel, d_nodes, d_poses, d_hits, threads);
  const double tri = rate(triangle_kernel, d_triangles, d_poses, d_hits, threads);
  std::printf("{\"gpu\":\"%s\",\"bv_tests_per_s\":%.4g,\"triangle_tests_per_s\":%.4g}\n",
              properties.name, bv, tri);
  return 0;
}
