/* sort_sweep.h — the pieces of the sort-and-sweep broadphase that kernels/sort_sweep.cl and
 * its CPU reference share: the per-lane sums of AABB centres and the axis chosen from them,
 * the order-preserving uint key of a float, and the value of a vector on the chosen axis. */
#ifndef BTG_SORT_SWEEP_H
#define BTG_SORT_SWEEP_H
#include "prelude.h"

#ifndef __OPENCL_C_VERSION__
#include <cstring>
#endif

/* Lanes of the one-work-group reduction of the centres (sap_axis). A fixed count, not the
 * device's group size, so the summation order, and with it the axis, is the same on every
 * device and in the reference: lane l sums rows l, l + L, l + 2L, ...; then a halving tree. */
#define BTG_SAP_LANES 64

/* Key of rows outside the sweep (not gridded): sorts after every swept row's key. */
#define BTG_SAP_NO_KEY 0xffffffffu

/* One row's contribution to its lane: xyz the centre and w 1 (counts rows) in `sum`, xyz the
 * squared centre in `sumSq`. Callers add these in lane order. */
static inline BtgFloat4 btgSapCentre(BtgFloat4 aMin, BtgFloat4 aMax)
{
    BtgFloat4 c = (aMin + aMax) * 0.5f;
    return btgMake4(c.x, c.y, c.z, 1.0f);
}

static inline BtgFloat4 btgSapSquare(BtgFloat4 c) { return btgMake4(c.x * c.x, c.y * c.y, c.z * c.z, 0.0f); }

/* The axis (0 x, 1 y, 2 z) along which the centres spread most (largest variance): along it
 * a row's sweep meets the fewest rows that do not overlap it. Ties go to the lower axis. */
static inline uint btgSapAxis(BtgFloat4 sum, BtgFloat4 sumSq)
{
    if (sum.w <= 0.0f) return 0u;
    float inv = 1.0f / sum.w;
    float mx = sum.x * inv, my = sum.y * inv, mz = sum.z * inv;
    float vx = sumSq.x * inv - mx * mx, vy = sumSq.y * inv - my * my, vz = sumSq.z * inv - mz * mz;
    uint axis = 0u;
    float best = vx;
    if (vy > best) { axis = 1u; best = vy; }
    if (vz > best) axis = 2u;
    return axis;
}

static inline float btgAxisValue(BtgFloat4 v, uint axis) { return axis == 0u ? v.x : (axis == 1u ? v.y : v.z); }

static inline uint btgFloatBits(float x)
{
#ifdef __OPENCL_C_VERSION__
    return as_uint(x);
#else
    uint u;
    std::memcpy(&u, &x, sizeof u);
    return u;
#endif
}

/* Orders like the floats: negative values have all bits flipped, others the sign bit set.
 * -0 becomes +0 first: they compare equal, so like other ties they stay in row order. The
 * largest key is left to BTG_SAP_NO_KEY (only a NaN gets near it: such a row sorts after the
 * finite ones, and its comparisons fail, so its sweep and any sweep reaching it stop). */
static inline uint btgSapKey(float x)
{
    uint u = btgFloatBits(x == 0.0f ? 0.0f : x);
    uint k = (u & 0x80000000u) ? ~u : (u | 0x80000000u);
    return k < BTG_SAP_NO_KEY ? k : BTG_SAP_NO_KEY - 1u;
}

#endif
