// Latency of a small GPU call's op sequence: current (many copies/memsets), consolidated, graph.
#include <cuda_runtime.h>
#include <cstdio>
#include <vector>
#include <algorithm>
#include <chrono>
__global__ void k_empty(int* p, int n) { if (threadIdx.x == 0 && blockIdx.x == 0 && p) p[0] += n; }
__global__ void k_work(int* p, int n) { int i = blockIdx.x * blockDim.x + threadIdx.x; if (i < n) p[i] += 1; }
#define C(x) do { cudaError_t e = (x); if (e) { printf("err %s line %d\n", cudaGetErrorString(e), __LINE__); return 1; } } while (0)
int main() {
  cudaStream_t s2; C(cudaStreamCreateWithFlags(&s2, cudaStreamNonBlocking));
  cudaEvent_t e0, e1, fork, join; C(cudaEventCreate(&e0)); C(cudaEventCreate(&e1));
  C(cudaEventCreateWithFlags(&fork, cudaEventDisableTiming)); C(cudaEventCreateWithFlags(&join, cudaEventDisableTiming));
  const int n = 256; const int width = 7, links = 13;
  float *hq, *hc; unsigned char* hv; int *hs, *hcount; char* hblock;
  C(cudaMallocHost(&hq, 4096 * 64)); C(cudaMallocHost(&hc, 4096 * 64)); C(cudaMallocHost(&hv, 4096)); C(cudaMallocHost(&hs, 256)); C(cudaMallocHost(&hcount, 64)); C(cudaMallocHost(&hblock, 1 << 20));
  float *dq, *dc; unsigned char* dv; int *ds, *dcount, *dwork; char* dblock;
  C(cudaMalloc(&dq, 4096 * 64)); C(cudaMalloc(&dc, 4096 * 64)); C(cudaMalloc(&dv, 4096)); C(cudaMalloc(&ds, 256)); C(cudaMalloc(&dcount, 64)); C(cudaMalloc(&dwork, 1 << 20)); C(cudaMalloc(&dblock, 1 << 20));
  auto current = [&](cudaStream_t st, bool ev = true) {
    if (ev) cudaEventRecord(e0, st);
    cudaMemcpyAsync(dq, hq, n * width * 4, cudaMemcpyHostToDevice, st);
    cudaMemcpyAsync(dc, hc, n * links * 4, cudaMemcpyHostToDevice, st);
    cudaMemsetAsync(dcount, 0, 16, st);
    cudaMemsetAsync(ds, 0, 200, st);
    cudaMemsetAsync(dv, 0, n, st);
    k_work<<<(n * 34 + 127) / 128, 128, 0, st>>>(dwork, n * 34);
    cudaEventRecord(fork, st); cudaStreamWaitEvent(s2, fork, 0);
    k_work<<<(n * 34 + 127) / 128, 128, 0, s2>>>(dwork + 100000, n * 34);
    k_work<<<132, 128, 0, s2>>>(dwork + 200000, 132 * 128);
    cudaEventRecord(join, s2);
    k_work<<<264, 256, 0, st>>>(dwork + 300000, 264 * 256);
    cudaStreamWaitEvent(st, join, 0);
    cudaMemcpyAsync(hs, ds, 200, cudaMemcpyDeviceToHost, st);
    cudaMemcpyAsync(hv, dv, n, cudaMemcpyDeviceToHost, st);
    cudaMemcpyAsync(hcount, dcount, 16, cudaMemcpyDeviceToHost, st);
    if (ev) cudaEventRecord(e1, st);
  };
  auto consolidated = [&](cudaStream_t st, bool ev = true) {
    if (ev) cudaEventRecord(e0, st);
    cudaMemcpyAsync(dblock, hblock, n * (width + links) * 4, cudaMemcpyHostToDevice, st);
    cudaMemsetAsync(dblock + 65536, 0, 256 + n, st);
    k_work<<<(n * 34 + 127) / 128, 128, 0, st>>>(dwork, n * 34);
    cudaEventRecord(fork, st); cudaStreamWaitEvent(s2, fork, 0);
    k_work<<<(n * 34 + 127) / 128, 128, 0, s2>>>(dwork + 100000, n * 34);
    k_work<<<132, 128, 0, s2>>>(dwork + 200000, 132 * 128);
    cudaEventRecord(join, s2);
    k_work<<<264, 256, 0, st>>>(dwork + 300000, 264 * 256);
    cudaStreamWaitEvent(st, join, 0);
    cudaMemcpyAsync(hblock + 65536, dblock + 65536, 256 + n, cudaMemcpyDeviceToHost, st);
    if (ev) cudaEventRecord(e1, st);
  };
  auto nocontain = [&](cudaStream_t st) {
    cudaEventRecord(e0, st);
    cudaMemcpyAsync(dblock, hblock, n * (width + links) * 4, cudaMemcpyHostToDevice, st);
    cudaMemsetAsync(dblock + 65536, 0, 256 + n, st);
    k_work<<<(n * 34 + 127) / 128, 128, 0, st>>>(dwork, n * 34);
    k_work<<<264, 256, 0, st>>>(dwork + 300000, 264 * 256);
    cudaMemcpyAsync(hblock + 65536, dblock + 65536, 256 + n, cudaMemcpyDeviceToHost, st);
    cudaEventRecord(e1, st);
  };
  auto bare = [&](cudaStream_t st) { cudaEventRecord(e0, st); k_empty<<<1, 32, 0, st>>>(nullptr, 0); cudaEventRecord(e1, st); };
  auto time_it = [&](const char* name, auto&& body, cudaStream_t st) {
    std::vector<double> wall, gpu;
    for (int r = 0; r < 2000; ++r) {
      auto t0 = std::chrono::steady_clock::now();
      body(st);
      cudaEventSynchronize(e1);
      auto t1 = std::chrono::steady_clock::now();
      float ms; cudaEventElapsedTime(&ms, e0, e1);
      if (r >= 100) { wall.push_back(std::chrono::duration<double>(t1 - t0).count() * 1e6); gpu.push_back(ms * 1e3); }
    }
    std::sort(wall.begin(), wall.end()); std::sort(gpu.begin(), gpu.end());
    printf("%-28s wall median %6.1f us p10 %6.1f p90 %6.1f | events %6.1f us\n", name, wall[wall.size() / 2], wall[wall.size() / 10], wall[wall.size() * 9 / 10], gpu[gpu.size() / 2]);
  };
  cudaStream_t st0 = 0, st1; C(cudaStreamCreateWithFlags(&st1, cudaStreamNonBlocking));
  time_it("bare (1 empty kernel)", bare, st0);
  time_it("current (default stream)", [&](cudaStream_t st) { current(st); }, st0);
  time_it("consolidated (default)", [&](cudaStream_t st) { consolidated(st); }, st0);
  time_it("no containment", nocontain, st0);
  time_it("current (own stream)", [&](cudaStream_t st) { current(st); }, st1);
  time_it("consolidated (own stream)", [&](cudaStream_t st) { consolidated(st); }, st1);
  // graph of the consolidated sequence
  for (int variant = 0; variant < 2; ++variant) {
    cudaGraph_t g; cudaGraphExec_t ge;
    C(cudaStreamBeginCapture(st1, cudaStreamCaptureModeGlobal));
    if (variant == 0) consolidated(st1, false); else current(st1, false);
    C(cudaStreamEndCapture(st1, &g));
    C(cudaGraphInstantiate(&ge, g, 0));
    time_it(variant == 0 ? "graph of consolidated" : "graph of current", [&](cudaStream_t st) { cudaEventRecord(e0, st); cudaGraphLaunch(ge, st); cudaEventRecord(e1, st); }, st1);
  }
  return 0;
}
