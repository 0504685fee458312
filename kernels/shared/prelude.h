/* prelude.h — the common ground of every shared header: it lets one source compile as
 * OpenCL C 1.2 (kernels) and as C++17 (host references and layout checks).
 * Vectors are BtgFloat4 (OpenCL float4 on the device, a 16-byte struct with operators on the
 * host); shared functions use only the operators and btg* helpers defined here, never the
 * OpenCL built-ins whose rounding is implementation-defined (dot, cross, normalize). */
#ifndef BTG_PRELUDE_H
#define BTG_PRELUDE_H

#ifdef __OPENCL_C_VERSION__
#pragma OPENCL FP_CONTRACT OFF
typedef float4 BtgFloat4;
typedef int4 BtgInt4;
#define BTG_GLOBAL __global
#define BTG_CONST_GLOBAL __global const
/* global memory another work-group writes within one launch (BTG_SHARED: volatile on GPUs,
 * see grid_barrier.h) */
#ifndef BTG_SHARED
#define BTG_SHARED volatile
#endif
#define BTG_SHARED_GLOBAL BTG_SHARED __global
#define BTG_INLINE inline
/* a hot row function whose by-value arguments (bodies, deltas, the step's scalars: hundreds of
 * bytes) a CPU device's compiler would otherwise copy onto the stack at every call */
#define BTG_ALWAYS_INLINE inline __attribute__((always_inline))
#define BTG_STATIC_ASSERT(cond, msg)
/* a loop over a private array's elements, unrolled: with its index known at compile time the
 * array stays in registers (an indexed private array lives in a GPU's local memory) */
#define BTG_UNROLL _Pragma("unroll")
static inline BtgFloat4 btgMake4(float x, float y, float z, float w) { return (float4)(x, y, z, w); }
static inline float btgSqrt(float x) { return sqrt(x); }
static inline float btgAbs(float x) { return fabs(x); }
static inline float btgSin(float x) { return sin(x); }
static inline float btgCos(float x) { return cos(x); }
static inline float btgPow(float x, float y) { return pow(x, y); }
static inline float btgAtan2(float y, float x) { return atan2(y, x); }
static inline float btgAcos(float x) { return acos(x); }
static inline float btgAsin(float x) { return asin(x); }
static inline float btgFmod(float x, float y) { return fmod(x, y); }
static inline float btgMin(float a, float b) { return fmin(a, b); }
static inline float btgMax(float a, float b) { return fmax(a, b); }
static inline int btgIsFinite(float x) { return isfinite(x); }
#else
#include <cmath>
#include <cstdint>
typedef unsigned int uint;
struct alignas(16) BtgFloat4 {
    float x, y, z, w;
};
struct alignas(16) BtgInt4 {
    int x, y, z, w;
};
#define BTG_GLOBAL
#define BTG_CONST_GLOBAL const
#define BTG_SHARED_GLOBAL
#define BTG_INLINE inline
#if defined(__GNUC__) || defined(__clang__)
#define BTG_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define BTG_ALWAYS_INLINE inline
#endif
#define BTG_STATIC_ASSERT(cond, msg) static_assert(cond, msg)
#define BTG_UNROLL
static inline BtgFloat4 btgMake4(float x, float y, float z, float w) { return BtgFloat4{x, y, z, w}; }
static inline BtgFloat4 operator+(BtgFloat4 a, BtgFloat4 b) { return {a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w}; }
static inline BtgFloat4 operator-(BtgFloat4 a, BtgFloat4 b) { return {a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w}; }
static inline BtgFloat4 operator-(BtgFloat4 a) { return {-a.x, -a.y, -a.z, -a.w}; }
static inline BtgFloat4 operator*(BtgFloat4 a, BtgFloat4 b) { return {a.x * b.x, a.y * b.y, a.z * b.z, a.w * b.w}; }
static inline BtgFloat4 operator*(BtgFloat4 a, float s) { return {a.x * s, a.y * s, a.z * s, a.w * s}; }
static inline BtgFloat4 operator*(float s, BtgFloat4 a) { return {a.x * s, a.y * s, a.z * s, a.w * s}; }
static inline BtgFloat4 operator/(BtgFloat4 a, float s) { return {a.x / s, a.y / s, a.z / s, a.w / s}; }
static inline BtgFloat4& operator+=(BtgFloat4& a, BtgFloat4 b) { a = a + b; return a; }
static inline BtgFloat4& operator-=(BtgFloat4& a, BtgFloat4 b) { a = a - b; return a; }
static inline BtgFloat4& operator*=(BtgFloat4& a, float s) { a = a * s; return a; }
static inline float btgSqrt(float x) { return std::sqrt(x); }
static inline float btgAbs(float x) { return std::fabs(x); }
static inline float btgSin(float x) { return std::sin(x); }
static inline float btgCos(float x) { return std::cos(x); }
static inline float btgPow(float x, float y) { return std::pow(x, y); }
static inline float btgAtan2(float y, float x) { return std::atan2(y, x); }
static inline float btgAcos(float x) { return std::acos(x); }
static inline float btgAsin(float x) { return std::asin(x); }
static inline float btgFmod(float x, float y) { return std::fmod(x, y); }
static inline float btgMin(float a, float b) { return std::fmin(a, b); }
static inline float btgMax(float a, float b) { return std::fmax(a, b); }
static inline int btgIsFinite(float x) { return std::isfinite(x) ? 1 : 0; }
#endif

/* Spelled-out products so host and device round the same way (contraction is off on both). */
static inline float btgDot3(BtgFloat4 a, BtgFloat4 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline BtgFloat4 btgCross3(BtgFloat4 a, BtgFloat4 b)
{
    return btgMake4(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x, 0.0f);
}
static inline float btgLength3(BtgFloat4 a) { return btgSqrt(btgDot3(a, a)); }
static inline BtgFloat4 btgXyz(BtgFloat4 a) { return btgMake4(a.x, a.y, a.z, 0.0f); }
static inline BtgFloat4 btgZero4(void) { return btgMake4(0.0f, 0.0f, 0.0f, 0.0f); }
static inline BtgFloat4 btgNormalize3(BtgFloat4 a)
{
    float l = btgLength3(a);
    return l > 0.0f ? btgXyz(a) * (1.0f / l) : btgMake4(1.0f, 0.0f, 0.0f, 0.0f);
}
static inline int btgIsFinite4(BtgFloat4 a)
{
    return btgIsFinite(a.x) && btgIsFinite(a.y) && btgIsFinite(a.z) && btgIsFinite(a.w);
}
static inline float btgClamp(float x, float lo, float hi) { return btgMin(btgMax(x, lo), hi); }

#endif
