/* contact_cache.cl — Stage: contacts (compaction of the pairs' manifolds and warm start) and,
 * after the solve, the warm-start cache for the next substep.
 * Launch: count_contacts / write_contacts one work-item per pair slot (pairCapacity), in
 * work-groups whose size the host passes as the local-memory scan size; scan_blocks as one
 * work-item; store_contact_cache one work-item per contact slot.
 * Reads pairManifolds (each pair's range of manifolds with points), manifolds,
 * counters[kPairCount, kPrevContactCount, kStatus], pos, rot, props (contact processing
 * thresholds, BTG_SOLVER_PROCESSING_THRESHOLD only; body flags, BTG_SOLVER_FRICTION_ANCHORS only),
 * contactCache, gjkPairState (friction anchors' points on A, BTG_SOLVER_FRICTION_ANCHORS only).
 * Writes blockSums (scratch), contacts and contactManifolds (the manifold slot of each),
 * counters[kContactCount], counters[kStatus]; then contactCache and counters[kPrevContactCount]. */
#include "shared/counters.h"
#include "shared/types.h"
#include "shared/math.h"
#include "shared/contact_rows.h"
#include "shared/pair_kinds.h"

/* The contacts of this work-item's pair: its manifolds with points. */
static uint pair_contacts(__global const BtgManifoldRange* restrict pairManifolds, __global const uint* restrict counters,
                          int pairCapacity)
{
    uint gid = (uint)get_global_id(0);
    uint n = min(counters[BTG_COUNTER_PAIRS], (uint)pairCapacity);
    return gid < n ? (uint)pairManifolds[gid].count : 0u;
}

/* Hillis-Steele inclusive scan of one value per work-item; integers, so any order is exact.
 * Returns the exclusive prefix; *total receives the group's sum. */
static uint group_exclusive_scan(uint v, __local uint* tmp, uint* total)
{
    uint lid = (uint)get_local_id(0), lsz = (uint)get_local_size(0);
    tmp[lid] = v;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint off = 1; off < lsz; off <<= 1) {
        uint add = lid >= off ? tmp[lid - off] : 0u;
        barrier(CLK_LOCAL_MEM_FENCE);
        tmp[lid] += add;
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    *total = tmp[lsz - 1];
    return tmp[lid] - v;
}

__kernel void count_contacts(__global const BtgManifoldRange* restrict pairManifolds, __global const uint* restrict counters,
                             int pairCapacity, __global uint* blockSums, __local uint* tmp)
{
    uint total;
    group_exclusive_scan(pair_contacts(pairManifolds, counters, pairCapacity), tmp, &total);
    if (get_local_id(0) == 0) blockSums[get_group_id(0)] = total;
}

/* Few blocks (pairCapacity / group size): one work-item scans them in order. */
__kernel void scan_blocks(__global uint* blockSums, int numBlocks, __global uint* counters, int contactCapacity)
{
    if (get_global_id(0) != 0) return;
    uint sum = 0;
    for (int i = 0; i < numBlocks; ++i) {
        uint v = blockSums[i];
        blockSums[i] = sum;
        sum += v;
    }
    counters[BTG_COUNTER_CONTACTS] = sum;
    if (sum > (uint)contactCapacity) counters[BTG_COUNTER_STATUS] |= BTG_STATUS_CONTACT_OVERFLOW;
}

/* A pair's contacts go to consecutive slots from its prefix, in its range's order. */
__kernel void write_contacts(__global const BtgManifoldRange* restrict pairManifolds,
                             __global const BtgManifold* restrict manifolds, __global const uint* restrict counters,
                             int pairCapacity, __global const uint* restrict blockSums,
                             __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,
                             __global const BtgBodyProps* restrict props,
                             __global const BtgCachedContact* restrict cache, int cacheCapacity,
                             __global BtgContact* contacts, __global uint* restrict contactManifolds, int contactCapacity,
                             __global const BtgPersistentManifold* restrict gjkPairState, int gjkCapacity,
                             BtgStepParams params, __local uint* tmp)
{
    uint count = pair_contacts(pairManifolds, counters, pairCapacity);
    uint total;
    uint local_index = group_exclusive_scan(count, tmp, &total);
    if (count == 0u) return;
    BtgManifoldRange range = pairManifolds[get_global_id(0)];
    uint first = blockSums[get_group_id(0)] + local_index;
    int prevCount = (int)min(counters[BTG_COUNTER_PREV_CONTACTS], (uint)cacheCapacity);
    for (uint j = 0; j < count; ++j) {
        uint dst = first + j;
        if (dst >= (uint)contactCapacity) return;
        uint slot = (uint)range.start + j;
        BtgManifold m = manifolds[slot];
        BtgContact c = btgContactFromManifold(m, pos[m.bodyA], pos[m.bodyB]);
        if ((params.solverFlags & BTG_SOLVER_FRICTION_ANCHORS) && slot < (uint)gjkCapacity &&
            btgAnchoredPair(props[m.bodyA].flags, props[m.bodyB].flags) && gjkPairState[slot].kind != BTG_PAIR_NONE)
            btgAnchorLeverArms(&c, gjkPairState[slot], pos[m.bodyA], rot[m.bodyA]);
        /* The entry this manifold had lies where the last substep's contacts lie as this one's:
         * the search starts at its own slot, and finds the bisection's entry from any start in a
         * cache in pair order (cache_search.h), which the pipeline's is. A bisection over the
         * whole cache for each contact was 40% of this kernel on PoCL at cubes 8,000. (Taken
         * back once, 2026-12-06: five warm-start tests failed, whose fixture's cache was out of
         * pair order, so its bisections missed entries too; contact_fixture.h now checks.) */
        int hint = (int)dst;
        int prev = btgFindPrevContactNear(cache, prevCount, m, &hint);
        /* the manifold's processing threshold only where a body has one (props untouched otherwise) */
        const float processing = (params.solverFlags & BTG_SOLVER_PROCESSING_THRESHOLD)
                                     ? btgProcessingThreshold(props[m.bodyA], props[m.bodyB])
                                     : BTG_NO_PROCESSING_THRESHOLD;
        if (prev >= 0) btgWarmStartFrom(&c, rot[m.bodyA], m, cache[prev], params.warmstartFactor, processing,
                                          (params.solverFlags & BTG_SOLVER_WARM_FRICTION) != 0u);
        contacts[dst] = c;
        contactManifolds[dst] = slot;
    }
}

/* After the solve, before the bodies move: the solved contacts become the next substep's cache,
 * written into `next` (the host then swaps the two buffers), with the entries carried through a
 * sleep merged in by pair key (carry_flags, carry_contact_cache): neither engine collides a pair
 * of sleeping or static bodies, and stock keeps such a pair's manifold, points and impulses,
 * through the sleep; so a woken pile warm-starts as stock's instead of starting cold. A substep
 * that overflowed, or whose one-launch solve gave up at its grid barrier, copies the cache as
 * it was instead, so the redo of a one-substep call finds it unchanged (its results are thrown
 * away anyway). cachePos[i]: where contact i's entry went (store_persistent_manifolds puts the
 * pair's manifold there too). */
static inline int btgSleepsOrStands(uint f)
{
    if (f & (BTG_BODY_EXCLUDED | BTG_BODY_NO_SHAPE)) return 0;
    if (f & BTG_BODY_STATIC) return 1;
    return (f & (BTG_BODY_DYNAMIC | BTG_BODY_KINEMATIC)) && (f & BTG_BODY_SLEEPING);
}

/* Before the wake (the flags as the pairs were found): rank[j] 1 for a cache entry whose bodies
 * both sleep or stand (its pair was not collided, and is not among this substep's contacts),
 * else 0, over all cacheCapacity + 1 entries; exclusive-scanned into ranks by the host. */
__kernel void carry_flags(__global const BtgCachedContact* restrict cache, __global const uint* restrict counters,
                          int cacheCapacity, int numBodies, __global const BtgBodyProps* restrict props,
                          __global uint* rank)
{
    const int j = get_global_id(0);
    if (j > cacheCapacity) return;
    const int prevCount = (int)min(counters[BTG_COUNTER_PREV_CONTACTS], (uint)cacheCapacity);
    uint flag = 0u;
    if (j < prevCount) {
        const int a = cache[j].bodyA, b = cache[j].bodyB;
        if (a >= 0 && b >= 0 && a < numBodies && b < numBodies && btgSleepsOrStands(props[a].flags) &&
            btgSleepsOrStands(props[b].flags))
            flag = 1u;
    }
    rank[j] = flag;
}

/* The first of contacts[0, n) whose pair key is not below (ka, kb). */
static inline uint btgContactsLowerBound(__global const BtgContact* restrict contacts, uint n, int ka, int kb)
{
    uint lo = 0u, hi = n;
    while (lo < hi) {
        const uint mid = lo + (hi - lo) / 2u;
        const int ma = contacts[mid].bodyA, mb = contacts[mid].bodyB;
        if (btgPairKeyLess(ma < mb ? ma : mb, ma < mb ? mb : ma, ka, kb)) lo = mid + 1u;
        else hi = mid;
    }
    return lo;
}

__kernel void store_contact_cache(__global const BtgContact* restrict contacts,
                                  __global const uint* restrict contactManifolds,
                                  __global const BtgManifold* restrict manifolds, __global const uint* restrict counters,
                                  int contactCapacity, __global const BtgFloat4* restrict rot,
                                  __global const BtgCachedContact* restrict cache, int cacheCapacity,
                                  __global BtgCachedContact* next, __global const uint* restrict rank, int carry,
                                  __global uint* cachePos)
{
    const uint i = (uint)get_global_id(0);
    const uint prevCount = min(counters[BTG_COUNTER_PREV_CONTACTS], (uint)cacheCapacity);
    if ((counters[BTG_COUNTER_STATUS] & BTG_STATUS_REDO) != 0u) {
        if (i < prevCount) next[i] = cache[i];
        return;
    }
    const uint n = min(counters[BTG_COUNTER_CONTACTS], (uint)min(contactCapacity, cacheCapacity));
    if (i >= n) return;
    const BtgContact c = contacts[i];
    uint pos = i;
    if (btgCarried(rank, carry, n, cacheCapacity) > 0u) {
        const int ka = min(c.bodyA, c.bodyB), kb = max(c.bodyA, c.bodyB);
        pos += rank[btgCachedLowerBound(cache, 0, (int)prevCount, ka, kb)];
    }
    next[pos] = btgCachedContactFrom(c, rot[c.bodyA], &manifolds[contactManifolds[i]]);
    cachePos[i] = pos;
}

__kernel void carry_contact_cache(__global const BtgCachedContact* restrict cache, __global const uint* restrict counters,
                                  int cacheCapacity, int contactCapacity, __global const BtgContact* restrict contacts,
                                  __global const uint* restrict rank, int carry, __global BtgCachedContact* next,
                                  __global uint* carryPos)
{
    const uint j = (uint)get_global_id(0);
    if ((counters[BTG_COUNTER_STATUS] & BTG_STATUS_REDO) != 0u) return;
    const uint prevCount = min(counters[BTG_COUNTER_PREV_CONTACTS], (uint)cacheCapacity);
    const uint n = min(counters[BTG_COUNTER_CONTACTS], (uint)min(contactCapacity, cacheCapacity));
    if (j >= prevCount || btgCarried(rank, carry, n, cacheCapacity) == 0u || rank[j + 1u] == rank[j]) return;
    const int a = cache[j].bodyA, b = cache[j].bodyB;
    const uint pos = rank[j] + btgContactsLowerBound(contacts, n, min(a, b), max(a, b));
    next[pos] = cache[j];
    carryPos[j] = pos;
}

/* The soft step's store wrote the new cache into its rows' storage (dead after its solve: the
 * world keeps one cache buffer): its entries back over the old ones. Under a redo the store
 * copied the old entries unchanged, so none move. */
__kernel void copy_cache_back(__global const BtgCachedContact* restrict stored, __global const uint* restrict counters,
                              int contactCapacity, int cacheCapacity, __global const uint* restrict rank, int carry,
                              __global BtgCachedContact* cache)
{
    const uint i = (uint)get_global_id(0);
    if ((counters[BTG_COUNTER_STATUS] & BTG_STATUS_REDO) != 0u) return;
    const uint n = min(counters[BTG_COUNTER_CONTACTS], (uint)min(contactCapacity, cacheCapacity));
    if (i < n + btgCarried(rank, carry, n, cacheCapacity)) cache[i] = stored[i];
}

/* Last, after both caches are written: the next substep's count of cached entries. */
__kernel void count_cache(__global uint* counters, int contactCapacity, int cacheCapacity,
                          __global const uint* restrict rank, int carry)
{
    if ((counters[BTG_COUNTER_STATUS] & BTG_STATUS_REDO) != 0u) return;
    const uint n = min(counters[BTG_COUNTER_CONTACTS], (uint)min(contactCapacity, cacheCapacity));
    counters[BTG_COUNTER_PREV_CONTACTS] = n + btgCarried(rank, carry, n, cacheCapacity);
}
