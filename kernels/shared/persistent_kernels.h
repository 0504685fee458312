/* persistent_kernels.h — the kernels of the narrowphase programs whose pairs keep a persistent
 * manifold (narrowphase_gjk.cl: the GJK kinds; narrowphase_sat.cl: two boxes): each collide
 * kernel (collide_persistent, one a program) reads the manifold its pair kept last substep, steps it (BTG_PERSISTENT_STEP, which the
 * program defines before including this) and writes it beside the pair's manifold, or with
 * `speculative` (the soft step) collides a pair BTG_SPECULATIVE_PAIR names afresh
 * (BTG_SPECULATIVE_COLLIDE) and keeps nothing; after the
 * solve, store_persistent_manifolds keeps those manifolds for the next substep. A program may also
 * expand collide_fresh (BTG_FRESH_PROGRAM_KERNEL) for the soft step's pairs it keeps nothing for.
 * OpenCL only. */
#ifndef BTG_PERSISTENT_KERNELS_H
#define BTG_PERSISTENT_KERNELS_H
#include "contact_rows.h"
#include "compound.h"
#include "mesh.h"
#include "persistent_manifold.h"

/* The pairs collide_fresh takes of those BTG_SPECULATIVE_PAIR names (BTG_FRESH_KERNEL 1): all,
 * unless the program says which. */
#ifndef BTG_FRESH_PAIR
#define BTG_FRESH_PAIR(kind, shapeA, shapeB) BTG_SPECULATIVE_PAIR(kind, shapeA, shapeB)
#endif
/* ... and how it collides them: BTG_SPECULATIVE_COLLIDE, unless the program names a routine of
 * its own for them (one without GJK's code, whose registers it would take). */
#ifndef BTG_FRESH_COLLIDE
#define BTG_FRESH_COLLIDE BTG_SPECULATIVE_COLLIDE
#endif

/* The manifold the pair kept last substep: found through the warm-start cache (the contacts in
 * pair order), whose entry j the GJK cache holds at j too. None when the pair had no points, or
 * the entry is another kind's (the pair's shapes changed). hint: btgFindPrevContactNear's. */
static BtgPersistentManifold btgPreviousManifold(BtgPair p, int kind, __global const BtgChild* restrict children,
                                               __global const uint* restrict counters,
                                               __global const BtgCachedContact* restrict cache, int cacheCapacity,
                                               __global const BtgPersistentManifold* restrict gjkCache,
                                               int gjkCapacity, int* hint)
{
    BtgManifold key = btgPairKeyManifold(p, children);
    const int prevCount = (int)min(counters[BTG_COUNTER_PREV_CONTACTS], (uint)min(cacheCapacity, gjkCapacity));
    const int j = btgFindPrevContactNear(cache, prevCount, key, hint);
    if (j >= 0) {
        BtgPersistentManifold prev = gjkCache[j];
        if (prev.bodyA == p.a && prev.bodyB == p.b && prev.kind == kind && prev.numPoints >= 0 &&
            prev.numPoints <= BTG_MAX_POINTS)
            return prev;
    }
    return btgEmptyPersistent(p.a, p.b, kind);
}

/* The kinds' ranges of the kind-grouped pairs laid end to end (a collide kernel strides over
 * them), those with `skip` set in skipMask (bit k: kinds[k]) left out: their total, and the
 * range slot of position idx (*kind its kind; BTG_PAIR_NONE past the end). */
static inline uint btgKindsTotal(const int* kinds, int numKinds, uint skipMask, __global const uint* restrict kindRanges)
{
    uint total = 0u;
    for (int k = 0; k < numKinds; ++k)
        if (!((skipMask >> k) & 1u))
            total += kindRanges[BTG_KIND_RANGE_END(kinds[k])] - kindRanges[BTG_KIND_RANGE_START(kinds[k])];
    return total;
}
static inline uint btgKindsAt(const int* kinds, int numKinds, uint skipMask, __global const uint* restrict kindRanges,
                              uint idx, int* kind)
{
    *kind = BTG_PAIR_NONE;
    uint rest = idx;
    for (int k = 0; k < numKinds; ++k) {
        if ((skipMask >> k) & 1u) continue;
        const uint first = kindRanges[BTG_KIND_RANGE_START(kinds[k])];
        const uint n = kindRanges[BTG_KIND_RANGE_END(kinds[k])] - first;
        if (rest < n) {
            *kind = kinds[k];
            return first + rest;
        }
        rest -= n;
    }
    return 0u;
}

/* The program's one collide kernel, collide_persistent, for every kind of its sub-table TABLE:
 * a work-item strides over the kinds' ranges laid end to end, so the step (GJK and EPA, the
 * featured hulls' clip, the box detector) is compiled once, not once a kind (NVIDIA's compiler
 * took minutes over the nine copies). On a CPU device a work-item takes a run of consecutive
 * pairs instead, each pair's last manifold sought from where the one before it was found
 * (btgFindPrevContactNear): a bisection over the whole cache for every pair, and the load of the
 * scattered entry it found, were a fifth of the kernel on PoCL. */
#ifdef BTG_CPU_DEVICE
#define BTG_PERSISTENT_RUNS 1
#else
#define BTG_PERSISTENT_RUNS 0
#endif
#define BTG_PERSISTENT_KIND_ITEM(program, kind, shapeA, shapeB, routine, kernel) kind,
#define BTG_PERSISTENT_PROGRAM_KERNEL(TABLE)                                                                         \
    __kernel void collide_persistent(__global const BtgPair* restrict pairs, __global const uint* restrict kindOrder, \
                                     __global const uint* restrict kindRanges, int indirect,                          \
                                     __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,  \
                                     __global const BtgBodyProps* restrict props,                                     \
                                     __global const BtgShape* restrict shapes,                                        \
                                     __global const BtgChild* restrict children,                                      \
                                     __global const BtgFloat4* restrict verts, __global const BtgFace* restrict faces, \
                                     __global const int* restrict indices, __global const BtgFloat4* restrict edges,  \
                                     __global const uint* restrict counters,                                          \
                                     __global const BtgCachedContact* restrict cache, int cacheCapacity,              \
                                     __global const BtgPersistentManifold* restrict gjkCache, int gjkCapacity,        \
                                     __global BtgManifold* restrict manifolds,                                        \
                                     __global BtgManifoldRange* restrict pairManifolds,                               \
                                     __global BtgPersistentManifold* restrict gjkPairState, int speculative,          \
                                     int stateCapacity)                                                               \
    {                                                                                                                 \
        const int kinds[] = {TABLE(BTG_PERSISTENT_KIND_ITEM)};                                                        \
        const int numKinds = (int)(sizeof(kinds) / sizeof(kinds[0]));                                                \
        /* the kinds collide_fresh takes whole in the soft step are not walked here at all */                         \
        uint skipMask = 0u;                                                                                           \
        for (int k = 0; k < numKinds; ++k)                                                                            \
            if (BTG_FRESH_KERNEL && speculative && BTG_SOFT_COLLIDES_AFRESH(kinds[k])) skipMask |= 1u << k;           \
        const uint total = btgKindsTotal(kinds, numKinds, skipMask, kindRanges);                                      \
        const uint per = BTG_PERSISTENT_RUNS ? (total + (uint)get_global_size(0) - 1u) / (uint)get_global_size(0) : 1u; \
        const uint start = BTG_PERSISTENT_RUNS ? (uint)get_global_id(0) * per : (uint)get_global_id(0);               \
        const uint stop = BTG_PERSISTENT_RUNS ? min(total, start + per) : total;                                      \
        const uint stride = BTG_PERSISTENT_RUNS ? 1u : (uint)get_global_size(0);                                      \
        int hint = BTG_PERSISTENT_RUNS ? 0 : -1; /* none on a GPU: its work-items' pairs lie far apart */          \
        for (uint idx = start; idx < stop; idx += stride) {                                                          \
            int kind;                                                                                                 \
            const uint i = btgKindsAt(kinds, numKinds, skipMask, kindRanges, idx, &kind);                             \
            const uint slot = indirect ? kindOrder[i] : i;                                                            \
            const BtgPair p = pairs[slot];                                                                            \
            BtgCollider a = btgLoadPairCollider(p, 0, pos, rot, props, shapes, children);                             \
            BtgCollider b = btgLoadPairCollider(p, 1, pos, rot, props, shapes, children);                             \
            const float t = btgPairThreshold(a.shape, b.shape);                                                       \
            BtgPersistentManifold pm = btgEmptyPersistent(p.a, p.b, kind);                                           \
            BtgManifold m = btgEmptyManifold(p.a, p.b);                                                               \
            if (BTG_FRESH_KERNEL && btgPairKind(a.shape.type, b.shape.type) == kind && speculative &&                 \
                BTG_FRESH_PAIR(kind, a.shape, b.shape))                                                               \
                continue; /* collide_fresh's */                                                                       \
            if (btgPairKind(a.shape.type, b.shape.type) == kind && speculative &&                                     \
                BTG_SPECULATIVE_PAIR(kind, a.shape, b.shape)) {                                                       \
                /* this step's own points, no manifold kept: kind NONE, which no pair takes */                        \
                m = BTG_SPECULATIVE_COLLIDE(a, b, verts, faces, indices, edges, t);                                   \
                pm = btgEmptyPersistent(p.a, p.b, BTG_PAIR_NONE);                                                     \
            } else if (btgPairKind(a.shape.type, b.shape.type) == kind) {                                             \
                float dist[BTG_MAX_POINTS];                                                                           \
                BtgPersistentManifold prev =                                                                          \
                    btgPreviousManifold(p, kind, children, counters, cache, cacheCapacity, gjkCache, gjkCapacity,      \
                                        &hint);                                                                       \
                if (p.childA != BTG_WHOLE_BODY || p.childB != BTG_WHOLE_BODY)                                         \
                    prev = btgChildPreRefresh(prev, a.pose, b.pose, t);                                               \
                pm = BTG_PERSISTENT_STEP(prev, a, b, verts, faces, indices, edges, t, dist);                          \
                m = btgManifoldFromPersistent(pm, dist, b.pose);                                                      \
            }                                                                                                         \
            m = btgWithChildKeys(btgWithThreshold(m, t), p, children);                                                \
            /* none held where no pair keeps a manifold (the soft step's boxes alone) */                              \
            if ((int)slot < stateCapacity) gjkPairState[slot] = pm;                                                   \
            manifolds[slot] = m;                                                                                      \
            pairManifolds[slot] = btgOneManifold((int)slot, m);                                                       \
        }                                                                                                             \
    }

/* The soft step's fresh pairs of a program whose collide_persistent leaves them (BTG_FRESH_KERNEL
 * 1): collide_fresh strides over the four kinds its arguments name (OpenCL C has no variadic
 * macros: NVIDIA's compiler refuses them), collides each pair BTG_FRESH_PAIR (of those
 * BTG_SPECULATIVE_PAIR names, the ones without GJK) names afresh (BTG_SPECULATIVE_COLLIDE) and
 * keeps nothing for it; the other pairs of those kinds are collide_persistent's. A kernel of its own: the closed forms on the GJK kernel's registers
 * ran at its occupancy. */
#define BTG_FRESH_PROGRAM_KERNEL(K0, K1, K2, K3)                                                                    \
    __kernel void collide_fresh(__global const BtgPair* restrict pairs, __global const uint* restrict kindOrder,     \
                                __global const uint* restrict kindRanges, int indirect,                              \
                                __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,      \
                                __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes, \
                                __global const BtgChild* restrict children,                                          \
                                __global const BtgFloat4* restrict verts, __global const BtgFace* restrict faces,    \
                                __global const int* restrict indices, __global const BtgFloat4* restrict edges,      \
                                __global BtgManifold* restrict manifolds,                                            \
                                __global BtgManifoldRange* restrict pairManifolds,                                   \
                                __global BtgPersistentManifold* restrict gjkPairState, int stateCapacity)            \
    {                                                                                                                 \
        const int kinds[] = {K0, K1, K2, K3};                                                                         \
        const int numKinds = (int)(sizeof(kinds) / sizeof(kinds[0]));                                                \
        const uint total = btgKindsTotal(kinds, numKinds, 0u, kindRanges);                                            \
        for (uint idx = (uint)get_global_id(0); idx < total; idx += (uint)get_global_size(0)) {                      \
            int kind;                                                                                                 \
            const uint i = btgKindsAt(kinds, numKinds, 0u, kindRanges, idx, &kind);                                   \
            const uint slot = indirect ? kindOrder[i] : i;                                                            \
            const BtgPair p = pairs[slot];                                                                            \
            BtgCollider a = btgLoadPairCollider(p, 0, pos, rot, props, shapes, children);                             \
            BtgCollider b = btgLoadPairCollider(p, 1, pos, rot, props, shapes, children);                             \
            if (btgPairKind(a.shape.type, b.shape.type) != kind || !BTG_FRESH_PAIR(kind, a.shape, b.shape))          \
                continue; /* collide_persistent's (or, a stale plan's, no kernel's: as there) */                      \
            const float t = btgPairThreshold(a.shape, b.shape);                                                       \
            BtgManifold m = BTG_FRESH_COLLIDE(a, b, verts, faces, indices, edges, t);                                 \
            m = btgWithChildKeys(btgWithThreshold(m, t), p, children);                                                \
            if ((int)slot < stateCapacity) gjkPairState[slot] = btgEmptyPersistent(p.a, p.b, BTG_PAIR_NONE);          \
            manifolds[slot] = m;                                                                                      \
            pairManifolds[slot] = btgOneManifold((int)slot, m);                                                       \
        }                                                                                                             \
    }

/* After store_contact_cache, with the same rule for a substep that must be redone: contact i's
 * pair's manifold goes to gjkCache[i], beside its warm-start entry, with the friction anchors
 * the next refresh keeps (btgAnchorMask, from the solved contact); a contact of another kind
 * gets an entry no pair takes. */
/* Which of contact c's points the next refresh keeps as friction anchors (replaceContactPoint):
 * with either body's CF_HAS_FRICTION_ANCHOR, those whose lateral impulses l1, l2 lie inside the
 * cone of their normal impulse n: not l1^2 + l2^2 > (mu n)^2 (eps 0, as 3.24). Bit id[k]. */
static uint btgAnchorMask(BtgContact c, BtgPersistentManifold pm, uint flags)
{
    uint mask = 0u;
    if ((flags & BTG_BODY_FRICTION_ANCHOR) == 0u) return mask;
    for (int k = 0; k < pm.numPoints && k < c.numPoints; ++k) {
        const float l1 = btgLane(c.friction1Impulse, k), l2 = btgLane(c.friction2Impulse, k);
        const float a = l1 * l1 + l2 * l2;
        float b = c.friction * btgLane(c.normalImpulse, k);
        b = b * b;
        if (!(a > b)) mask |= 1u << pm.id[k];
    }
    return mask;
}

__kernel void store_persistent_manifolds(__global const uint* restrict contactManifolds,
                                         __global const BtgManifold* restrict manifolds,
                                         __global const uint* restrict counters, int contactCapacity,
                                         __global const BtgBodyProps* restrict props,
                                         __global const BtgShape* restrict shapes, __global const BtgPair* restrict pairs,
                                         __global const BtgChild* restrict children,
                                         __global const BtgPersistentManifold* restrict gjkPairState, int pairCapacity,
                                         __global BtgPersistentManifold* restrict gjkCache, int gjkCapacity,
                                         __global const BtgContact* restrict contacts, uint solverFlags, uint base,
                                         __global const BtgSubPair* restrict subPairs, uint subPairCapacity,
                                         __global BtgPersistentManifold* restrict gjkNext,
                                         __global const uint* restrict cachePos)
{
    const uint i = (uint)get_global_id(0);
    /* as store_contact_cache, which keeps the cache as it was then (copied into the buffer the
       host swaps in): the two caches share indices */
    if ((counters[BTG_COUNTER_STATUS] & BTG_STATUS_REDO) != 0u) {
        if (i < min(counters[BTG_COUNTER_PREV_CONTACTS], (uint)gjkCapacity)) gjkNext[i] = gjkCache[i];
        return;
    }
    const uint n = min(counters[BTG_COUNTER_CONTACTS], (uint)min(contactCapacity, gjkCapacity));
    if (i >= n) return;
    const uint slot = contactManifolds[i];
    const BtgManifold m = manifolds[slot];
    BtgPersistentManifold pm = btgEmptyPersistent(m.bodyA, m.bodyB, BTG_PAIR_NONE);
    /* the (leaf) pair whose manifold this is: its own slot, or a convex–concave pair's group */
    const uint pairSlot = btgManifoldPair(slot, base, subPairs, subPairCapacity);
    if (pairSlot < (uint)pairCapacity) {
        /* the kind of the pair, which wrote gjkPairState[pairSlot] if a persistent kind */
        const BtgPair p = pairs[pairSlot];
        if (btgHasPersistentState(p, gjkPairState[pairSlot], props, shapes, children)) pm = gjkPairState[pairSlot];
    }
    pm.anchorMask = 0u;
    if ((solverFlags & BTG_SOLVER_FRICTION_ANCHORS) != 0u && pm.kind != BTG_PAIR_NONE)
        pm.anchorMask = btgAnchorMask(contacts[i], pm, props[m.bodyA].flags | props[m.bodyB].flags);
    const uint pos = cachePos[i];
    if (pos < (uint)gjkCapacity) gjkNext[pos] = pm;
}

/* The manifolds of the entries store_contact_cache carried through a sleep, to the same places
 * (carryPos), before count_cache sets the new count. */
__kernel void carry_persistent_manifolds(__global const BtgPersistentManifold* restrict gjkCache, int gjkCapacity,
                                         __global const uint* restrict counters, int cacheCapacity, int contactCapacity,
                                         __global const uint* restrict rank, __global const uint* restrict carryPos,
                                         __global BtgPersistentManifold* restrict gjkNext)
{
    const uint j = (uint)get_global_id(0);
    if ((counters[BTG_COUNTER_STATUS] & BTG_STATUS_REDO) != 0u) return;
    const uint prevCount = min(counters[BTG_COUNTER_PREV_CONTACTS], (uint)min(cacheCapacity, gjkCapacity));
    const uint n = min(counters[BTG_COUNTER_CONTACTS], (uint)min(contactCapacity, cacheCapacity));
    if (j >= prevCount || btgCarried(rank, 1, n, cacheCapacity) == 0u || rank[j + 1u] == rank[j]) return;
    const uint pos = carryPos[j];
    if (pos < (uint)gjkCapacity) gjkNext[pos] = gjkCache[j];
}

#endif
