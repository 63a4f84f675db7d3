#pragma once
// GP_HD marks functions compiled for both host and device: the geometry core is one
// body of code, tested on the CPU and run on the GPU.

#if defined(__CUDACC__)
#define GP_HD __host__ __device__ __forceinline__
#else
#define GP_HD inline
#endif
