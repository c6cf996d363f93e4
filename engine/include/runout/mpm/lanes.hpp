#pragma once
// Four doubles side by side: one row of a particle's stencil (the nodes
// first .. first + 3 along x of shape.hpp, the fourth with zero weight),
// which the hot stages compute and add as one value. Under g++ and clang
// it is a GNU vector, one AVX register (two SSE2 ones on the x86-64
// baseline): GCC 12 left the same arithmetic, written node by node or as
// loops over a row, scalar, because the nodal arrays may alias. Under nvcc
// it is four doubles, each lane a thread's scalar work.
#include <cmath>
#include <cstring>

#include "runout/mpm/host_device.hpp"

// Lanes as four plain doubles: under nvcc and compilers without GNU vectors.
#if defined(__CUDACC__) || !defined(__GNUC__)
#define RUNOUT_LANES_SCALAR 1
#endif

#if defined(RUNOUT_LIBMVEC) && defined(__AVX2__) && !defined(RUNOUT_LANES_SCALAR)
// glibc's libmvec, four doubles in an AVX register (the x86_64 vector ABI's
// names for exp and log).
typedef double RunoutVector4d __attribute__((vector_size(4 * sizeof(double))));
extern "C" RunoutVector4d _ZGVdN4v_exp(RunoutVector4d);
extern "C" RunoutVector4d _ZGVdN4v_log(RunoutVector4d);
#endif

namespace runout {

#ifdef RUNOUT_LANES_SCALAR
struct Lanes {
  double v[4];
};

RUNOUT_HD inline Lanes load_lanes(const double* a) { return {{a[0], a[1], a[2], a[3]}}; }
RUNOUT_HD inline Lanes gather_lanes(const double* a, const int* i) {
  return {{a[i[0]], a[i[1]], a[i[2]], a[i[3]]}};
}
RUNOUT_HD inline Lanes splat(double x) { return {{x, x, x, x}}; }
RUNOUT_HD inline double lane(const Lanes& a, int k) { return a.v[k]; }

template <class Op>
RUNOUT_HD inline Lanes lanewise(const Lanes& a, const Lanes& b, Op op) {
  return {{op(a.v[0], b.v[0]), op(a.v[1], b.v[1]), op(a.v[2], b.v[2]), op(a.v[3], b.v[3])}};
}
struct LaneAdd {
  RUNOUT_HD double operator()(double x, double y) const { return x + y; }
};
struct LaneMul {
  RUNOUT_HD double operator()(double x, double y) const { return x * y; }
};
struct LaneDiv {
  RUNOUT_HD double operator()(double x, double y) const { return x / y; }
};
RUNOUT_HD inline Lanes operator+(const Lanes& a, const Lanes& b) { return lanewise(a, b, LaneAdd{}); }
RUNOUT_HD inline Lanes operator*(const Lanes& a, const Lanes& b) { return lanewise(a, b, LaneMul{}); }
RUNOUT_HD inline Lanes operator/(const Lanes& a, const Lanes& b) { return lanewise(a, b, LaneDiv{}); }
// The lanes' sums of four values, (a0 + a1) + (a2 + a3) for a and so on.
RUNOUT_HD inline Lanes lane_sums(const Lanes& a, const Lanes& b, const Lanes& c, const Lanes& d) {
  const Lanes* in[4] = {&a, &b, &c, &d};
  Lanes r;
  for (int k = 0; k < 4; ++k) r.v[k] = (in[k]->v[0] + in[k]->v[1]) + (in[k]->v[2] + in[k]->v[3]);
  return r;
}
// a < b ? x : y, lane by lane.
RUNOUT_HD inline Lanes select_less(const Lanes& a, const Lanes& b, const Lanes& x, const Lanes& y) {
  Lanes r;
  for (int k = 0; k < 4; ++k) r.v[k] = a.v[k] < b.v[k] ? x.v[k] : y.v[k];
  return r;
}
#else
struct Lanes {
  typedef double Vector __attribute__((vector_size(4 * sizeof(double))));
  Vector v;
};

inline Lanes load_lanes(const double* a) {
  Lanes r;
  std::memcpy(&r.v, a, sizeof r.v);  // unaligned: a row starts at any node
  return r;
}
inline Lanes gather_lanes(const double* a, const int* i) {
  return {Lanes::Vector{a[i[0]], a[i[1]], a[i[2]], a[i[3]]}};
}
inline Lanes splat(double x) { return {Lanes::Vector{x, x, x, x}}; }
inline double lane(const Lanes& a, int k) { return a.v[k]; }
inline Lanes operator+(const Lanes& a, const Lanes& b) { return {a.v + b.v}; }
inline Lanes operator*(const Lanes& a, const Lanes& b) { return {a.v * b.v}; }
inline Lanes operator/(const Lanes& a, const Lanes& b) { return {a.v / b.v}; }
inline Lanes select_less(const Lanes& a, const Lanes& b, const Lanes& x, const Lanes& y) {
  return {a.v < b.v ? x.v : y.v};
}
// Four horizontal sums at once, as a 4 x 4 transpose: pairs within each
// vector, then the pairs' halves. Six vector operations, where each sum
// alone takes three extractions and three scalar adds.
inline Lanes lane_sums(const Lanes& a, const Lanes& b, const Lanes& c, const Lanes& d) {
  // {a0 + a1, b0 + b1, a2 + a3, b2 + b3} and the same of c and d
  const Lanes::Vector ab = __builtin_shufflevector(a.v, b.v, 0, 4, 2, 6) +
                           __builtin_shufflevector(a.v, b.v, 1, 5, 3, 7);
  const Lanes::Vector cd = __builtin_shufflevector(c.v, d.v, 0, 4, 2, 6) +
                           __builtin_shufflevector(c.v, d.v, 1, 5, 3, 7);
  return {__builtin_shufflevector(ab, cd, 0, 1, 4, 5) + __builtin_shufflevector(ab, cd, 2, 3, 6, 7)};
}
#endif

RUNOUT_HD inline Lanes operator*(const Lanes& a, double x) { return a * splat(x); }
RUNOUT_HD inline Lanes operator*(double x, const Lanes& a) { return splat(x) * a; }
RUNOUT_HD inline Lanes operator+(const Lanes& a, double x) { return a + splat(x); }
RUNOUT_HD inline Lanes operator+(double x, const Lanes& a) { return splat(x) + a; }
RUNOUT_HD inline Lanes operator-(const Lanes& a) { return a * -1.0; }
RUNOUT_HD inline Lanes operator-(double x, const Lanes& a) { return splat(x) + -a; }
RUNOUT_HD inline Lanes operator-(const Lanes& a, const Lanes& b) { return a + -b; }
RUNOUT_HD inline Lanes operator-(const Lanes& a, double x) { return a + -x; }

RUNOUT_HD inline Lanes operator/(const Lanes& a, double x) { return a / splat(x); }
RUNOUT_HD inline Lanes operator/(double x, const Lanes& a) { return splat(x) / a; }

// The square root of a double, or lane by lane (correctly rounded either
// way, so each lane is the scalar result; one instruction with AVX), for
// the arithmetic written once for both. Host and device alike where Lanes
// are four plain doubles, as the templates that call it are.
RUNOUT_HD inline double square_root(double a) { return std::sqrt(a); }
#ifdef RUNOUT_LANES_SCALAR
RUNOUT_HD inline Lanes square_root(const Lanes& a) {
  return {{std::sqrt(a.v[0]), std::sqrt(a.v[1]), std::sqrt(a.v[2]), std::sqrt(a.v[3])}};
}
#elif defined(__AVX__)
inline Lanes square_root(const Lanes& a) { return {__builtin_ia32_sqrtpd256(a.v)}; }
#else
inline Lanes square_root(const Lanes& a) {
  return {{std::sqrt(lane(a, 0)), std::sqrt(lane(a, 1)), std::sqrt(lane(a, 2)), std::sqrt(lane(a, 3))}};
}
#endif

// exp and log lane by lane: glibc's vector forms (libmvec) in builds for
// AVX2 (RUNOUT_LIBMVEC, set by CMake where the library is found), within
// a few ulp of the scalar functions (tested); the scalar functions
// otherwise. The stress update's strength law evaluates an exp and a pow
// per particle and step: the pow of the rate factor was 15 % of a case 3
// run, and libmvec's own pow (its accurate path) took 11 %.
#if defined(RUNOUT_LIBMVEC) && defined(__AVX2__) && !defined(RUNOUT_LANES_SCALAR)
inline Lanes exp_lanes(const Lanes& a) { return {_ZGVdN4v_exp(a.v)}; }
inline Lanes log_lanes(const Lanes& a) { return {_ZGVdN4v_log(a.v)}; }
#else
inline Lanes exp_lanes(const Lanes& a) {
  return {{std::exp(lane(a, 0)), std::exp(lane(a, 1)), std::exp(lane(a, 2)), std::exp(lane(a, 3))}};
}
inline Lanes log_lanes(const Lanes& a) {
  return {{std::log(lane(a, 0)), std::log(lane(a, 1)), std::log(lane(a, 2)), std::log(lane(a, 3))}};
}
#endif

inline Lanes floor_lanes(const Lanes& a) {
#if defined(__AVX__) && !defined(__CUDACC__)
  return {__builtin_ia32_roundpd256(a.v, 0x09)};  // toward -infinity, no inexact exception
#else
  return {{std::floor(lane(a, 0)), std::floor(lane(a, 1)), std::floor(lane(a, 2)), std::floor(lane(a, 3))}};
#endif
}

// (x0, x0 + h, x0 + 2 h, x0 + 3 h): the offsets of a row's nodes.
RUNOUT_HD inline Lanes lane_offsets(double x0, double h) {
#ifdef RUNOUT_LANES_SCALAR
  return {{x0, x0 + h, x0 + 2.0 * h, x0 + 3.0 * h}};
#else
  return {Lanes::Vector{x0, x0 + h, x0 + 2.0 * h, x0 + 3.0 * h}};
#endif
}

// In place: lane k of v[j] becomes lane j of v[k].
inline void transpose_lanes(Lanes v[4]) {
#ifdef RUNOUT_LANES_SCALAR
  for (int j = 0; j < 4; ++j)
    for (int k = j + 1; k < 4; ++k) {
      const double t = v[j].v[k];
      v[j].v[k] = v[k].v[j];
      v[k].v[j] = t;
    }
#else
  const Lanes::Vector t0 = __builtin_shufflevector(v[0].v, v[1].v, 0, 4, 2, 6);
  const Lanes::Vector t1 = __builtin_shufflevector(v[0].v, v[1].v, 1, 5, 3, 7);
  const Lanes::Vector t2 = __builtin_shufflevector(v[2].v, v[3].v, 0, 4, 2, 6);
  const Lanes::Vector t3 = __builtin_shufflevector(v[2].v, v[3].v, 1, 5, 3, 7);
  v[0].v = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  v[1].v = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  v[2].v = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  v[3].v = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
#endif
}

RUNOUT_HD inline void store_lanes(double* a, const Lanes& v) {
#ifdef RUNOUT_LANES_SCALAR
  for (int k = 0; k < 4; ++k) a[k] = v.v[k];
#else
  std::memcpy(a, &v.v, sizeof v.v);  // one (unaligned) vector store
#endif
}

// The host backends' scatter: plain adds, race-free by the OpenMP
// backend's colouring and by the serial backend's single thread. A row
// is added as one vector: four loads, adds and stores become one each.
struct PlainAdd {
  void operator()(double* a, int n, double v) const { a[n] += v; }
  void operator()(double* a, int n0, const Lanes& v) const {
    store_lanes(a + n0, load_lanes(a + n0) + v);
  }
};

}  // namespace runout
