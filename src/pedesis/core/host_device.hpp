#pragma once
// Functions that the CUDA kernels (src/pedesis/gpu/) share with the CPU engine carry
// PEDESIS_HD: compiled for both sides by nvcc, plain functions for the C++ compiler.
// Headers that use it stay C++17 (Debian's nvcc 11.8 compiles no C++20).
#if defined(__CUDACC__)
#define PEDESIS_HD __host__ __device__
#else
#define PEDESIS_HD
#endif
