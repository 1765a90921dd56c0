#pragma once
// Functions that the CUDA kernels (src/pedesis/gpu/) share with the CPU engine carry
// PEDESIS_HD: compiled for both sides by nvcc, plain functions for the C++ compiler.
// Headers that use it stay C++17 (Debian's nvcc 11.8 compiles no C++20).
#if defined(__CUDACC__)
#define PEDESIS_HD __host__ __device__
#else
#define PEDESIS_HD
#endif

// The same, always inlined: for functions the CPU's SIMD kernels call with vector types
// (soft/pair_rows.hpp), which must be compiled inside each kernel for its instruction set.
#if defined(__CUDACC__)
#define PEDESIS_HD_INLINE __host__ __device__ __forceinline__
#elif defined(__GNUC__)
#define PEDESIS_HD_INLINE [[gnu::always_inline]] inline
#else
#define PEDESIS_HD_INLINE inline
#endif
