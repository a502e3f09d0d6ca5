// AALAB_HD: marks a function that compiles for the CPU and, under nvcc, for the GPU too, so
// that arithmetic both sides run has one text (methods/smaa_shader.h, compiled by
// methods/smaa.cpp and methods/cuda/smaa.cu). Empty in a host-only build.
#pragma once

#if defined(__CUDACC__)
#define AALAB_HD __host__ __device__
#else
#define AALAB_HD
#endif
