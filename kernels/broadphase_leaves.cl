/* broadphase_leaves.cl — stock's broadphase pairs on the device: each row's Dbvt leaf as
 * btDbvtBroadphase keeps it (shared/broadphase_leaves.h), the pairs whose leaves overlap (a
 * sweep along x over the leaves sorted by their lower bound), sorted by (a, b), and what changed
 * against the last call's list, compacted in list order so that only that travels to the host.
 * When no leaf moved in the call the pairs are the last call's (as stock adds pairs only for
 * leaves that moved, and drops them only then): the kernels after the update return at once.
 * Stage: broadphase_leaves (only while the fill wants stock's empty manifolds). Launch: per
 * kernel below. Reads: pos, rot, linVel, angVel (damped: right after predict_motion), props,
 * shapes. Writes: the LeafBuffers columns (src/world/leaf_buffers.h) and their counts. */
#include "shared/broadphase_leaves.h"
#include "shared/counters.h"

/* Launch: one work-item per body row, every substep. reset: the leaf starts as createProxy
 * makes it (the shape's AABB without the threshold) before this step's setAabb. */
__kernel void leaves_update(int n, __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,
                            __global const BtgFloat4* restrict linVel, __global const BtgFloat4* restrict angVel,
                            __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                            __global BtgFloat4* leafMin, __global BtgFloat4* leafMax, __global uint* moved,
                            volatile __global uint* counts, float threshold, float dt, int continuous, int reset)
{
    int i = (int)get_global_id(0);
    if (i >= n) return;
    BtgBodyProps p = props[i];
    if (p.flags & BTG_BODY_EXCLUDED) {
        BtgAabb e = btgEmptyAabb();
        leafMin[i] = e.lo;
        leafMax[i] = e.hi;
        return;
    }
    BtgShape s = shapes[p.shape];
    BtgAabb leaf;
    if (reset) {
        leaf = btgLeafShapeAabb(pos[i], rot[i], s, p.flags, 0.0f);
    } else {
        leaf.lo = leafMin[i];
        leaf.hi = leafMax[i];
    }
    BtgAabb a = btgStockAabb(pos[i], rot[i], linVel[i], angVel[i], s, p.flags, threshold, dt, continuous);
    if (btgLeafUpdate(&leaf, a)) {
        moved[i] = 1u;
        atomic_inc(&counts[BTG_LEAF_MOVED]);
    }
    leafMin[i] = leaf.lo;
    leafMax[i] = leaf.hi;
}

/* Launch: one work-item per body row. */
__kernel void leaves_sweep_keys(int n, __global const BtgBodyProps* restrict props,
                                __global const BtgFloat4* restrict leafMin, __global uint* keys, __global uint* rows)
{
    int i = (int)get_global_id(0);
    if (i >= n) return;
    keys[i] = (props[i].flags & BTG_BODY_EXCLUDED) ? (1u << BTG_LEAF_SWEEP_BITS) - 1u : btgLeafSweepKey(leafMin[i].x);
    rows[i] = (uint)i;
}

/* Launch: one work-item per sorted leaf: it against the leaves after it until one starts past
 * its upper x bound (by sweep key). Every overlap counts towards m_newpairs once per moved side (stock's tree
 * collider counts before the pair cache filters); the allowed ones are appended. */
__kernel void leaves_sweep(int n, __global const uint* restrict rows, __global const BtgBodyProps* restrict props,
                           __global const BtgFloat4* restrict leafMin, __global const BtgFloat4* restrict leafMax,
                           __global const uint* restrict moved, __global BtgPair* raw, volatile __global uint* counts,
                           uint capacity)
{
    int i = (int)get_global_id(0);
    if (i >= n || counts[BTG_LEAF_MOVED] == 0u) return;
    int r = (int)rows[i];
    BtgBodyProps pr = props[r];
    if (pr.flags & BTG_BODY_EXCLUDED) return;
    BtgAabb lr;
    lr.lo = leafMin[r];
    lr.hi = leafMax[r];
    uint movedR = moved[r];
    uint last = btgLeafSweepKey(lr.hi.x);
    uint newPairs = 0u;
    for (int j = i + 1; j < n; ++j) {
        int s = (int)rows[j];
        BtgBodyProps ps = props[s];
        if (ps.flags & BTG_BODY_EXCLUDED) break; /* they sort last */
        BtgAabb ls;
        ls.lo = leafMin[s];
        ls.hi = leafMax[s];
        if (btgLeafSweepKey(ls.lo.x) > last) break;
        if (!btgLeafMeets(lr, ls)) continue;
        newPairs += movedR + moved[s];
        if (!btgLeafPairAllowed(pr, ps)) continue;
        uint slot = atomic_inc(&counts[BTG_LEAF_FOUND]);
        if (slot < capacity) {
            BtgPair q;
            q.a = r < s ? r : s;
            q.b = r < s ? s : r;
            q.childA = BTG_WHOLE_BODY;
            q.childB = BTG_WHOLE_BODY;
            raw[slot] = q;
        }
    }
    if (newPairs) atomic_add(&counts[BTG_LEAF_NEWPAIRS], newPairs);
}

/* Launch: one work-item per pair slot (capacity). Keys as find_pairs' pair_sort_keys: mode
 * BTG_PAIR_KEY_PACKED (a << bits) | b; MINOR b (first of two stable passes); MAJOR the a of the
 * pair the first pass put at this slot. Slots past the count sort last. */
__kernel void leaves_pair_keys(__global const BtgPair* restrict raw, __global const uint* restrict counts,
                               __global uint* keys, __global uint* order, uint capacity, int mode, int bits)
{
    uint i = (uint)get_global_id(0);
    if (i >= capacity) return;
    uint count = min(counts[BTG_LEAF_FOUND], capacity);
    if (i >= count) {
        keys[i] = 0xffffffffu;
        if (mode != BTG_PAIR_KEY_MAJOR) order[i] = i;
        return;
    }
    if (mode == BTG_PAIR_KEY_PACKED) {
        keys[i] = ((uint)raw[i].a << bits) | (uint)raw[i].b;
        order[i] = i;
    } else if (mode == BTG_PAIR_KEY_MINOR) {
        keys[i] = (uint)raw[i].b;
        order[i] = i;
    } else {
        keys[i] = (uint)raw[order[i]].a;
    }
}

/* Launch: one work-item per pair slot (capacity). */
__kernel void leaves_pairs_write(__global const BtgPair* restrict raw, __global const uint* restrict order,
                                 __global const uint* restrict counts, __global BtgPair* next, uint capacity)
{
    uint i = (uint)get_global_id(0);
    if (i >= min(counts[BTG_LEAF_FOUND], capacity) || counts[BTG_LEAF_MOVED] == 0u) return;
    next[i] = raw[order[i]];
}

/* Launch: one work-item per slot of both lists (2 x capacity): this list's pairs the last one
 * lacks, then the last list's pairs this one lacks. */
__kernel void leaves_diff_flags(__global const BtgPair* restrict next, __global const BtgPair* restrict prev,
                                __global const uint* restrict counts, __global uint* flags, __global uint* offsets,
                                uint capacity)
{
    uint i = (uint)get_global_id(0);
    if (i >= 2u * capacity || counts[BTG_LEAF_MOVED] == 0u) return;
    int numNext = (int)min(counts[BTG_LEAF_FOUND], capacity);
    int numPrev = (int)counts[BTG_LEAF_PREV];
    uint f = 0u;
    if (i < capacity) f = (int)i < numNext && !btgLeafPairIn(prev, numPrev, next[i]);
    else f = (int)(i - capacity) < numPrev && !btgLeafPairIn(next, numNext, prev[i - capacity]);
    flags[i] = f;
    offsets[i] = f;
}

/* Launch: one work-item per slot of both lists (2 x capacity), after the scan of offsets. */
__kernel void leaves_diff_write(__global const BtgPair* restrict next, __global const BtgPair* restrict prev,
                                __global const uint* restrict flags, __global const uint* restrict offsets,
                                __global const uint* restrict counts, __global BtgPair* changes, uint capacity)
{
    uint i = (uint)get_global_id(0);
    if (i >= 2u * capacity || counts[BTG_LEAF_MOVED] == 0u || !flags[i]) return;
    BtgPair q = i < capacity ? next[i] : prev[i - capacity];
    q.childA = i < capacity ? 1 : 0;
    changes[offsets[i]] = q;
}

/* Launch: one work-item. */
__kernel void leaves_diff_count(__global const uint* restrict flags, __global const uint* restrict offsets,
                                __global uint* counts, uint capacity)
{
    if (get_global_id(0) != 0) return;
    if (counts[BTG_LEAF_MOVED] == 0u) {
        counts[BTG_LEAF_ADDED] = 0u;
        counts[BTG_LEAF_REMOVED] = 0u;
        return;
    }
    uint last = 2u * capacity - 1u;
    uint total = offsets[last] + flags[last];
    counts[BTG_LEAF_ADDED] = offsets[capacity];
    counts[BTG_LEAF_REMOVED] = total - offsets[capacity];
}
