/* find_pairs.cl — broadphase: uniform-grid pairs of small bodies, large bodies against every
 * body, planes against every body; unsorted pairs appended with an atomic counter, then sorted
 * by the key (kind, a, b) with prims/radix_sort (launched from the host between these kernels),
 * least significant digits first: after the (a, b) passes the pairs are gathered into `pairs`
 * (the order of manifolds, contacts and the cache), and the kind pass then groups their slots
 * into kindOrder, each kind's range found on the device (kindRanges).
 * Stage: broadphase. Launch: per kernel below (bodies, sorted grid entries, pair slots or kinds).
 * Reads: aabbMin, aabbMax, props, shapes, children (a leaf pair's kind), pos, rot, largeBodies, planeBodies.
 * Writes: pairs, pairManifolds (empty), kindOrder, kindRanges, counters[BTG_COUNTER_PAIRS] (all pairs found, even past
 * capacity), counters[BTG_COUNTER_STATUS] (BTG_STATUS_PAIR_OVERFLOW), and the scratch of
 * BroadphaseScratch. */
#include "shared/broadphase.h"
#include "shared/compound.h"

#define BTG_NO_KEY 0xffffffffu

/* Launch: one work-item. Runs before every appending kernel. */
__kernel void pairs_reset(__global uint* counters)
{
    if (get_global_id(0) == 0) counters[BTG_COUNTER_PAIRS] = 0u;
}

/* Launch: one work-item per body row. Key: the cell hash, or BTG_NO_KEY (sorts last). */
__kernel void grid_hash(__global const BtgFloat4* restrict aabbMin, __global const BtgFloat4* restrict aabbMax,
                        __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                        __global uint* restrict keys, __global uint* restrict rows, int numBodies,
                        float invCellSize, uint tableMask)
{
    int i = (int)get_global_id(0);
    if (i >= numBodies) return;
    uint key = BTG_NO_KEY;
    if (btgGridded(props[i], shapes)) {
        BtgInt4 c = btgGridCell(aabbMin[i], aabbMax[i], invCellSize);
        key = btgGridHash(c.x, c.y, c.z, tableMask);
    }
    keys[i] = key;
    rows[i] = (uint)i;
}

/* Launch: one work-item per sorted grid entry. cellRange (zeroed before) gets, per hash, the
 * [start, end) of its entries in the sorted list. */
__kernel void grid_cell_ranges(__global const uint* restrict keys, __global uint* restrict cellRange, int numBodies)
{
    int k = (int)get_global_id(0);
    if (k >= numBodies) return;
    uint h = keys[k];
    if (h == BTG_NO_KEY) return;
    if (k == 0 || keys[k - 1] != h) cellRange[2 * h] = (uint)k;
    if (k == numBodies - 1 || keys[k + 1] != h) cellRange[2 * h + 1] = (uint)(k + 1);
}

/* Launch: one work-item per sorted grid entry. Scans its own cell and the 13 neighbour cells
 * after it (in z, y, x order) of the 27 (each bucket once, though hash collisions map several
 * cells to it): a pair of bodies in two cells is found from the lower cell, a pair in one cell
 * by its lower row; a body met in a bucket through a collision is kept only where its own cell
 * says so. Each pair once, as (lower row, higher row); the pair sort orders them after, so the
 * list is the one the full 27 cells gave (PoCL cubes 8,000: the stage's visits halved). */
__kernel void grid_pairs(__global const BtgFloat4* restrict aabbMin, __global const BtgFloat4* restrict aabbMax,
                         __global const BtgBodyProps* restrict props, __global const uint* restrict keys,
                         __global const uint* restrict rows, __global const uint* restrict cellRange,
                         __global BtgPair* restrict raw, volatile __global uint* counters,
                         uint capacity, int numBodies, float invCellSize, uint tableMask)
{
    int k = (int)get_global_id(0);
    if (k >= numBodies || keys[k] == BTG_NO_KEY) return;
    int i = (int)rows[k];
    BtgFloat4 iMin = aabbMin[i], iMax = aabbMax[i];
    BtgBodyProps pi = props[i];
    BtgInt4 c = btgGridCell(iMin, iMax, invCellSize);
    uint seen[14];
    int numSeen = 0;
    for (int dz = 0; dz <= 1; ++dz)
        for (int dy = dz == 0 ? 0 : -1; dy <= 1; ++dy)
            for (int dx = dz == 0 && dy == 0 ? 0 : -1; dx <= 1; ++dx) {
                uint h = btgGridHash(c.x + dx, c.y + dy, c.z + dz, tableMask);
                int dup = 0;
                for (int s = 0; s < numSeen; ++s) dup |= seen[s] == h;
                if (dup) continue;
                seen[numSeen++] = h;
                uint end = cellRange[2 * h + 1];
                for (uint m = cellRange[2 * h]; m < end; ++m) {
                    int j = (int)rows[m];
                    if (j == i) continue;
                    const BtgFloat4 jMin = aabbMin[j], jMax = aabbMax[j];
                    if (!btgAabbOverlap(iMin, iMax, jMin, jMax)) continue;
                    /* j's cell against i's, in z, y, x order: lower, or the same and a lower row,
                     * and i is not the one that keeps the pair */
                    const BtgInt4 cj = btgGridCell(jMin, jMax, invCellSize);
                    const int order = cj.z != c.z ? (cj.z > c.z ? 1 : -1)
                                      : cj.y != c.y ? (cj.y > c.y ? 1 : -1)
                                      : cj.x != c.x ? (cj.x > c.x ? 1 : -1)
                                                    : (j > i ? 1 : -1);
                    if (order < 0) continue;
                    if (!btgPairAllowed(pi, props[j])) continue;
                    btgAppendPair(raw, counters, capacity, min(i, j), max(i, j));
                }
            }
}

/* Launch: one work-item per body row: that body against every large body. A pair of two
 * large bodies is kept by its lower row only. */
__kernel void large_pairs(__global const BtgFloat4* restrict aabbMin, __global const BtgFloat4* restrict aabbMax,
                          __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                          __global const int* restrict largeBodies, int numLarge, __global BtgPair* restrict raw,
                          volatile __global uint* counters, uint capacity, int numBodies)
{
    int i = (int)get_global_id(0);
    if (i >= numBodies) return;
    BtgBodyProps pi = props[i];
    if ((pi.flags & BTG_BODY_EXCLUDED) || shapes[pi.shape].type == BTG_SHAPE_PLANE) return;
    int iLarge = (pi.flags & BTG_BODY_LARGE) != 0;
    BtgFloat4 iMin = aabbMin[i], iMax = aabbMax[i];
    for (int l = 0; l < numLarge; ++l) {
        int j = largeBodies[l];
        if (j == i || (iLarge && j < i)) continue;
        if (!btgAabbOverlap(iMin, iMax, aabbMin[j], aabbMax[j])) continue;
        if (!btgPairAllowed(pi, props[j])) continue;
        btgAppendPair(raw, counters, capacity, i, j);
    }
}

/* Launch: one work-item per body row: that body against every plane. */
__kernel void plane_pairs(__global const BtgFloat4* restrict aabbMin, __global const BtgFloat4* restrict aabbMax,
                          __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                          __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,
                          __global const int* restrict planeBodies, int numPlanes, __global BtgPair* restrict raw,
                          volatile __global uint* counters, uint capacity, int numBodies)
{
    int i = (int)get_global_id(0);
    if (i >= numBodies) return;
    BtgBodyProps pi = props[i];
    if ((pi.flags & BTG_BODY_EXCLUDED) || shapes[pi.shape].type == BTG_SHAPE_PLANE) return;
    BtgFloat4 iMin = aabbMin[i], iMax = aabbMax[i];
    for (int l = 0; l < numPlanes; ++l) {
        int j = planeBodies[l];
        BtgBodyProps pj = props[j];
        if (!btgPairAllowed(pi, pj)) continue;
        BtgFloat4 plane = btgPlaneWorld(pos[j], rot[j], shapes[pj.shape].param);
        if (!btgAabbReachesPlane(iMin, iMax, plane)) continue;
        btgAppendPair(raw, counters, capacity, i, j);
    }
}

/* Launch: one work-item per pair slot (capacity). Sort keys for the stored pairs, slots past
 * them padded with BTG_NO_KEY. mode 0: (a << bits) | b in one key (when 2 bits <= 32), order
 * = identity; mode 1: b, order = identity (first of two stable passes); mode 2: a of the
 * pair that the first pass put at this slot (order kept). */
__kernel void pair_sort_keys(__global const BtgPair* restrict raw, __global uint* restrict order,
                             __global uint* restrict keys, __global const uint* restrict counters,
                             uint capacity, int mode, uint bits)
{
    uint k = get_global_id(0);
    if (k >= capacity) return;
    uint count = min(counters[BTG_COUNTER_PAIRS], capacity);
    if (mode == BTG_PAIR_KEY_MAJOR) {
        keys[k] = k < count ? (uint)raw[order[k]].a : BTG_NO_KEY;
        return;
    }
    order[k] = k;
    if (k >= count) {
        keys[k] = BTG_NO_KEY;
        return;
    }
    BtgPair p = raw[k];
    keys[k] = mode == BTG_PAIR_KEY_PACKED ? (((uint)p.a << bits) | (uint)p.b) : (uint)p.b;
}

/* Launch: one work-item per pair slot (capacity). Gathers the sorted pairs into the world's
 * list, gives each no manifolds yet (the narrowphase of its kind gives it its range) and flags
 * an overflow. */
__kernel void pairs_write(__global const BtgPair* restrict raw, __global const uint* restrict order,
                          __global BtgPair* restrict pairs, __global BtgManifoldRange* restrict pairManifolds,
                          __global uint* counters, uint capacity)
{
    uint k = get_global_id(0);
    uint total = counters[BTG_COUNTER_PAIRS];
    if (k == 0 && total > capacity) atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_PAIR_OVERFLOW);
    if (k < min(total, capacity)) {
        pairs[k] = raw[order[k]];
        BtgManifoldRange none;
        none.start = (int)k;
        none.count = 0;
        pairManifolds[k] = none;
    }
}

/* Launch: one work-item per pair slot (capacity). The kind digit of the sort key, for the pairs
 * already in (a, b) order: key = the pair's kind (BTG_NO_KEY past the count), value = its slot. */
__kernel void pair_kind_keys(__global const BtgPair* restrict pairs, __global const BtgBodyProps* restrict props,
                             __global const BtgShape* restrict shapes, __global const BtgChild* restrict children,
                             __global const uint* restrict counters,
                             __global uint* restrict keys, __global uint* restrict order, uint capacity)
{
    uint k = get_global_id(0);
    if (k >= capacity) return;
    order[k] = k;
    if (k >= min(counters[BTG_COUNTER_PAIRS], capacity)) {
        keys[k] = BTG_NO_KEY;
        return;
    }
    keys[k] = (uint)btgPairKindOf(pairs[k], props, shapes, children);
}

/* Launch: one work-item per pair kind (BTG_NUM_PAIR_KINDS). Kind k's [start, end) in the kind
 * order: a binary search of the sorted kind keys; or, when the scene has one kind only
 * (singleKind >= 0, nothing sorted, kindOrder unused), every pair for it and none for the rest. */
__kernel void pair_kind_ranges(__global const uint* restrict keys, __global const uint* restrict counters,
                               uint capacity, int singleKind, __global uint* restrict kindRanges)
{
    int kind = (int)get_global_id(0);
    if (kind >= BTG_NUM_PAIR_KINDS) return;
    uint count = min(counters[BTG_COUNTER_PAIRS], capacity);
    uint start = 0u, end = 0u;
    if (singleKind >= 0) {
        end = kind == singleKind ? count : 0u;
    } else {
        uint lo = 0u, hi = count;  /* first key >= kind */
        while (lo < hi) {
            uint mid = lo + (hi - lo) / 2u;
            if (keys[mid] < (uint)kind) lo = mid + 1u;
            else hi = mid;
        }
        start = lo;
        hi = count;  /* first key > kind */
        while (lo < hi) {
            uint mid = lo + (hi - lo) / 2u;
            if (keys[mid] <= (uint)kind) lo = mid + 1u;
            else hi = mid;
        }
        end = lo;
    }
    kindRanges[BTG_KIND_RANGE_START(kind)] = start;
    kindRanges[BTG_KIND_RANGE_END(kind)] = end;
}
