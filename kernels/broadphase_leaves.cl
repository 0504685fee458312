/* broadphase_leaves.cl — stock's broadphase pairs on the device: each row's Dbvt leaf as
 * btDbvtBroadphase keeps it (shared/broadphase_leaves.h), the pairs whose leaves overlap (a grid
 * of (y, z) cells, each swept along x; rows too big for it against every row), sorted by (a, b),
 * and what changed against the last call's list, appended apart so that only that travels to
 * the host. When no leaf moved in the call the pairs are the last call's (as stock adds pairs
 * only for leaves that moved, and drops them only then): the kernels after the update return.
 * Stage: broadphase_leaves (only while the fill wants stock's empty manifolds). Launch: per
 * kernel below. Reads: pos, rot, linVel, angVel (damped: right after predict_motion), props,
 * shapes. Writes: the LeafBuffers columns (src/world/leaf_buffers.h) and their counts. */
#include "shared/broadphase_leaves.h"
#include "shared/counters.h"
#include "shared/group_append.h"

/* Launch: one work-item per body row, every substep. reset: the leaf starts as createProxy
 * makes it (the shape's AABB without the threshold) before this step's setAabb. */
__kernel void leaves_update(int n, __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,
                            __global const BtgFloat4* restrict linVel, __global const BtgFloat4* restrict angVel,
                            __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                            __global BtgFloat4* leafMin, __global BtgFloat4* leafMax, __global BtgFloat4* oldMin,
                            __global BtgFloat4* oldMax, __global uint* moved, volatile __global uint* counts,
                            float threshold, float dt, int continuous, int reset)
{
    int i = (int)get_global_id(0);
    if (i >= n) return;
    BtgBodyProps p = props[i];
    if (p.flags & BTG_BODY_EXCLUDED) {
        BtgAabb e = btgEmptyAabb();
        leafMin[i] = oldMin[i] = e.lo;
        leafMax[i] = oldMax[i] = e.hi;
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
    oldMin[i] = leaf.lo; /* as the rows updated before this one in stock's pass meet it */
    oldMax[i] = leaf.hi;
    BtgAabb a = btgStockAabb(pos[i], rot[i], linVel[i], angVel[i], s, p.flags, threshold, dt, continuous);
    if (btgLeafUpdate(&leaf, a)) {
        moved[i] = 1u;
        atomic_inc(&counts[BTG_LEAF_MOVED]);
    }
    leafMin[i] = leaf.lo;
    leafMax[i] = leaf.hi;
}

static inline BtgPair btgLeafPair(int r, int s)
{
    BtgPair q;
    q.a = r < s ? r : s;
    q.b = r < s ? s : r;
    q.childA = BTG_WHOLE_BODY;
    q.childB = BTG_WHOLE_BODY;
    return q;
}
/* Appends the pair (r, s) to a list counted in counts[slot] (every pair counted, stored while it fits). */
static inline void btgLeafAppend(__global BtgPair* raw, volatile __global uint* counts, int countSlot, uint capacity,
                                 int r, int s)
{
    uint slot = atomic_inc(&counts[countSlot]);
    if (slot < capacity) raw[slot] = btgLeafPair(r, s);
}

/* A candidate pair (its boxes old and new leaf together meet): what stock's pass of setAabb
 * calls made of it. btgLeafJudge (shared) gives its m_newpairs share; the pair goes to the list
 * when its leaves meet now (through the group's buffer where `group` is given: leaves_sweep on a
 * CPU device), to the transient list when only a moved leaf met the other's then. */
#define LEAF_GROUP_ARGS __local BtgPair *groupPairs, __local uint *groupCount
static inline uint btgLeafTake(int r, int s, __global const BtgFloat4* leafMin, __global const BtgFloat4* leafMax,
                               __global const BtgFloat4* oldMin, __global const BtgFloat4* oldMax,
                               __global const uint* moved, __global const BtgBodyProps* props, __global BtgPair* raw,
                               __global BtgPair* transient, volatile __global uint* counts, uint capacity,
                               int group, LEAF_GROUP_ARGS)
{
    int p = r < s ? r : s, q = r < s ? s : r;
    BtgAabb np, nq, oq;
    np.lo = leafMin[p];
    np.hi = leafMax[p];
    nq.lo = leafMin[q];
    nq.hi = leafMax[q];
    oq.lo = oldMin[q];
    oq.hi = oldMax[q];
    int meets = 0;
    uint share = btgLeafJudge(np, nq, oq, moved[p], moved[q], &meets);
    if (!btgLeafPairAllowed(props[p], props[q])) return share;
    if (meets && group) btgGroupAppend(groupPairs, groupCount, raw, &counts[BTG_LEAF_FOUND], capacity, btgLeafPair(p, q));
    else if (meets) btgLeafAppend(raw, counts, BTG_LEAF_FOUND, capacity, p, q);
    else if (share) btgLeafAppend(transient, counts, BTG_LEAF_TRANSIENT, capacity, p, q);
    return share;
}

/* Launch: one work-item per body row. Its entries (4 slots a row): one per (y, z) cell its leaf
 * overlaps, key (cell hash, sweep key of the leaf's lower x), value 4 row + which of its cells;
 * unused slots sort last. A row whose leaf spans more than two cells on y or z (a ground, a
 * plane, a large row) has none and joins the large list instead. */
__kernel void leaves_entries(int n, __global const BtgBodyProps* restrict props,
                             __global const BtgShape* restrict shapes, __global const BtgFloat4* restrict leafMin,
                             __global const BtgFloat4* restrict leafMax, __global const BtgFloat4* restrict oldMin,
                             __global const BtgFloat4* restrict oldMax, __global uint* keys, __global uint* values,
                             __global int* large, __global uint* isLarge, volatile __global uint* counts,
                             float invCell)
{
    int r = (int)get_global_id(0);
    if (r >= n) return;
    for (int k = 0; k < 4; ++k) {
        keys[4 * r + k] = BTG_LEAF_NO_ENTRY;
        values[4 * r + k] = (uint)(4 * r + k);
    }
    isLarge[r] = 0u;
    BtgBodyProps p = props[r];
    if (counts[BTG_LEAF_MOVED] == 0u || (p.flags & BTG_BODY_EXCLUDED)) return;
    BtgAabb u = btgLeafUnion(leafMin[r], leafMax[r], oldMin[r], oldMax[r]);
    BtgFloat4 lo = u.lo, hi = u.hi;
    BtgInt4 c0 = btgLeafCell(lo, invCell), c1 = btgLeafCell(hi, invCell);
    if ((p.flags & BTG_BODY_LARGE) || shapes[p.shape].type == BTG_SHAPE_PLANE || c1.y - c0.y > 1 || c1.z - c0.z > 1) {
        isLarge[r] = 1u;
        large[atomic_inc(&counts[BTG_LEAF_LARGE])] = r;
        return;
    }
    uint x = btgLeafSweepKey(lo.x);
    for (int k = 0; k < 4; ++k) {
        int cy = c0.y + (k & 1), cz = c0.z + (k >> 1);
        if (cy <= c1.y && cz <= c1.z) keys[4 * r + k] = (btgLeafCellHash(cy, cz) << BTG_LEAF_SWEEP_BITS) | x;
    }
}

/* Launch: one work-item per sorted entry: it against the entries after it in its cell until one
 * starts past its upper x bound (by sweep key). A pair is taken in one cell only, the one holding
 * the lower corner of the leaves' overlap in y and z (both leaves have an entry there), so it is
 * found once. Every overlap counts towards m_newpairs once per moved side (stock's tree collider
 * counts before the pair cache filters); the allowed ones are appended. */
/* One sorted entry's sweep (leaves_sweep); returns its m_newpairs share. */
static uint leaves_sweep_entry(int i, int numEntries, __global const uint* restrict keys,
                               __global const uint* restrict values, __global const BtgBodyProps* restrict props,
                               __global const BtgFloat4* restrict leafMin, __global const BtgFloat4* restrict leafMax,
                               __global const BtgFloat4* restrict oldMin, __global const BtgFloat4* restrict oldMax,
                               __global const uint* restrict moved, __global BtgPair* raw, __global BtgPair* transient,
                               volatile __global uint* counts, uint capacity, float invCell, int group,
                               LEAF_GROUP_ARGS)
{
    if (i >= numEntries) return 0u;
    uint key = keys[i];
    if (key == BTG_LEAF_NO_ENTRY) return 0u;
    uint v = values[i];
    int r = (int)(v >> 2);
    BtgAabb ur = btgLeafUnion(leafMin[r], leafMax[r], oldMin[r], oldMax[r]);
    BtgInt4 c0 = btgLeafCell(ur.lo, invCell);
    int cy = c0.y + (int)(v & 1u), cz = c0.z + (int)((v >> 1) & 1u);
    uint cell = key >> BTG_LEAF_SWEEP_BITS;
    uint last = btgLeafSweepKey(ur.hi.x);
    uint newPairs = 0u;
    for (int j = i + 1; j < numEntries; ++j) {
        uint kj = keys[j];
        if ((kj >> BTG_LEAF_SWEEP_BITS) != cell || (kj & ((1u << BTG_LEAF_SWEEP_BITS) - 1u)) > last) break;
        uint vj = values[j];
        int s = (int)(vj >> 2);
        if (s == r) continue; /* two of its cells share a hash */
        BtgAabb us = btgLeafUnion(leafMin[s], leafMax[s], oldMin[s], oldMax[s]);
        if (!btgLeafMeets(ur, us)) continue;
        BtgInt4 corner = btgLeafCell(btgMake4(0.0f, btgMax(ur.lo.y, us.lo.y), btgMax(ur.lo.z, us.lo.z), 0.0f), invCell);
        BtgInt4 s0 = btgLeafCell(us.lo, invCell);
        int sy = s0.y + (int)(vj & 1u), sz = s0.z + (int)((vj >> 1) & 1u);
        if (corner.y != cy || corner.z != cz || corner.y != sy || corner.z != sz) continue;
        newPairs += btgLeafTake(r, s, leafMin, leafMax, oldMin, oldMax, moved, props, raw, transient, counts, capacity,
                                group, groupPairs, groupCount);
    }
    return newPairs;
}
/* Launch: one work-item per sorted entry: it against the entries after it in its cell until one
 * starts past its upper x bound (by sweep key). A pair is taken in one cell only, the one holding
 * the lower corner of the leaves' overlap in y and z (both leaves have an entry there), so it is
 * found once. Every overlap counts towards m_newpairs once per moved side (stock's tree collider
 * counts before the pair cache filters); the allowed ones are appended (on a CPU device through
 * the work-group's buffer, group_append.h). */
__kernel void leaves_sweep(int numEntries, __global const uint* restrict keys, __global const uint* restrict values,
                           __global const BtgBodyProps* restrict props, __global const BtgFloat4* restrict leafMin,
                           __global const BtgFloat4* restrict leafMax, __global const BtgFloat4* restrict oldMin,
                           __global const BtgFloat4* restrict oldMax, __global const uint* restrict moved,
                           __global BtgPair* raw, __global BtgPair* transient, volatile __global uint* counts,
                           uint capacity, float invCell)
{
    const int i = (int)get_global_id(0);
    /* every work-item reads the same count: a group returns whole */
    if (counts[BTG_LEAF_MOVED] == 0u) return;
#ifdef BTG_CPU_DEVICE
    __local BtgPair groupPairs[BTG_GROUP_APPEND_ROOM];
    __local uint groupCount, groupBase, groupNew;
    btgGroupAppendBegin(&groupCount, &groupNew);
    const uint newPairs = leaves_sweep_entry(i, numEntries, keys, values, props, leafMin, leafMax, oldMin, oldMax, moved,
                                             raw, transient, counts, capacity, invCell, 1, groupPairs, &groupCount);
    if (newPairs) atomic_add(&groupNew, newPairs);
    btgGroupAppendEnd(groupPairs, &groupCount, &groupBase, raw, &counts[BTG_LEAF_FOUND], capacity, &groupNew,
                      &counts[BTG_LEAF_NEWPAIRS]);
#else
    const uint newPairs = leaves_sweep_entry(i, numEntries, keys, values, props, leafMin, leafMax, oldMin, oldMax, moved,
                                             raw, transient, counts, capacity, invCell, 0, 0, 0);
    if (newPairs) atomic_add(&counts[BTG_LEAF_NEWPAIRS], newPairs);
#endif
}

/* Launch: one work-item per body row: it against every large row (a pair of two large rows taken
 * by the higher one). */
__kernel void leaves_large(int n, __global const int* restrict large, __global const uint* restrict isLarge,
                           __global const BtgBodyProps* restrict props, __global const BtgFloat4* restrict leafMin,
                           __global const BtgFloat4* restrict leafMax, __global const BtgFloat4* restrict oldMin,
                           __global const BtgFloat4* restrict oldMax, __global const uint* restrict moved,
                           __global BtgPair* raw, __global BtgPair* transient, volatile __global uint* counts,
                           uint capacity)
{
    int s = (int)get_global_id(0);
    if (s >= n || counts[BTG_LEAF_MOVED] == 0u) return;
    if (props[s].flags & BTG_BODY_EXCLUDED) return;
    BtgAabb us = btgLeafUnion(leafMin[s], leafMax[s], oldMin[s], oldMax[s]);
    int numLarge = (int)counts[BTG_LEAF_LARGE];
    uint newPairs = 0u;
    for (int k = 0; k < numLarge; ++k) {
        int r = large[k];
        if (r == s || (isLarge[s] && s < r)) continue;
        if (!btgLeafMeets(btgLeafUnion(leafMin[r], leafMax[r], oldMin[r], oldMax[r]), us)) continue;
        newPairs += btgLeafTake(r, s, leafMin, leafMax, oldMin, oldMax, moved, props, raw, transient, counts, capacity,
                                0, 0, 0);
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

/* Launch: one work-item per `span` slots of each list (2 x ceil(capacity / span) in all): this
 * list's pairs the last one lacks are appended to changes[0, capacity), the last list's pairs
 * this one lacks to changes[capacity, 2 capacity); the host puts each part in (a, b) order (they
 * are few). A work-item finds its first pair in the other list by bisection and walks on from
 * there (a CPU device: spans of many pairs; a GPU: one). */
__kernel void leaves_diff(__global const BtgPair* restrict next, __global const BtgPair* restrict prev,
                          volatile __global uint* counts, __global BtgPair* changes, uint capacity, int span)
{
    const uint id = (uint)get_global_id(0), perList = (capacity + (uint)span - 1u) / (uint)span;
    if (id >= 2u * perList || counts[BTG_LEAF_MOVED] == 0u) return;
    const int numNext = (int)min(counts[BTG_LEAF_FOUND], capacity);
    const int numPrev = (int)counts[BTG_LEAF_PREV];
    const int removed = id >= perList; /* the last list's pairs */
    __global const BtgPair* restrict mine = removed ? prev : next;
    __global const BtgPair* restrict other = removed ? next : prev;
    const int nMine = removed ? numPrev : numNext, nOther = removed ? numNext : numPrev;
    const int begin = (int)(id - (removed ? perList : 0u)) * span, end = min(begin + span, nMine);
    if (begin >= end) return;
    int at = btgLeafLowerBound(other, nOther, mine[begin]);
    for (int i = begin; i < end; ++i) {
        BtgPair q = mine[i];
        while (at < nOther && btgLeafPairLess(other[at], q)) ++at;
        if (btgLeafPairAt(other, nOther, at, q)) continue;
        q.childA = removed ? 0 : 1;
        if (removed) changes[capacity + atomic_inc(&counts[BTG_LEAF_REMOVED])] = q;
        else changes[atomic_inc(&counts[BTG_LEAF_ADDED])] = q;
    }
}
