#pragma once
// Functions marked RUNOUT_HD are compiled for the host and, under nvcc, for
// the device too, so the per-particle and per-node stages have one source.
#if defined(__CUDACC__)
#define RUNOUT_HD __host__ __device__
#else
#define RUNOUT_HD
#endif
