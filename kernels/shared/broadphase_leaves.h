/* broadphase_leaves.h — stock's broadphase leaves, shared by kernels/broadphase_leaves.cl and its
 * CPU reference: the AABB btCollisionWorld::updateSingleAabb gives a row (its shape at the
 * current transform, unioned with the predicted one for a moving dynamic body, grown by the
 * contact threshold) and the Dbvt leaf btDbvtBroadphase::setAabb keeps for it (kept while it
 * contains that AABB, else the AABB fattened by gDbvtMargin; the AABB itself when they no
 * longer meet, setAabb's teleport). Stock's pairs are the pairs whose leaves overlap. */
#ifndef BTG_BROADPHASE_LEAVES_H
#define BTG_BROADPHASE_LEAVES_H
#include "aabb.h"
#include "broadphase.h"
#include "math.h"
#include "types.h"
#ifndef __OPENCL_C_VERSION__
#include <cstring>
#endif

/* Slots of the stage's own counts buffer (leafCounts), read back after a call. */
#define BTG_LEAF_FOUND 0    /* overlapping leaf pairs found (may exceed the list's capacity) */
#define BTG_LEAF_PREV 1     /* pairs in the previous call's sorted list */
#define BTG_LEAF_ADDED 2    /* pairs in this list and not in the previous one */
#define BTG_LEAF_REMOVED 3  /* pairs in the previous list and not in this one */
#define BTG_LEAF_NEWPAIRS 4 /* btDbvtBroadphase::m_newpairs: overlaps met by the leaves that moved */
#define BTG_LEAF_MOVED 5    /* leaves that moved in this call (setAabb's docollide) */
#define BTG_LEAF_LARGE 6    /* rows in the large list (too big for the sweep's cells) */
#define BTG_LEAF_TRANSIENT 7 /* pairs stock's pass added whose leaves no longer meet at its end */
#define BTG_LEAF_NUM_COUNTS 8

#define BTG_DBVT_MARGIN 0.05f   /* gDbvtMargin */
#define BTG_LARGE_FLOAT 1e30f   /* BT_LARGE_FLOAT: btStaticPlaneShape's AABB */

/* The row's shape AABB grown by `threshold`, or for a plane stock's +-BT_LARGE_FLOAT box. */
static inline BtgAabb btgLeafShapeAabb(BtgFloat4 pos, BtgFloat4 rot, BtgShape shape, uint flags, float threshold)
{
    if (shape.type == BTG_SHAPE_PLANE && !(flags & BTG_BODY_EXCLUDED)) {
        BtgAabb a;
        a.lo = btgMake4(-BTG_LARGE_FLOAT, -BTG_LARGE_FLOAT, -BTG_LARGE_FLOAT, 0.0f);
        a.hi = btgMake4(BTG_LARGE_FLOAT, BTG_LARGE_FLOAT, BTG_LARGE_FLOAT, 0.0f);
        return a;
    }
    return btgBodyAabb(pos, rot, shape, flags, threshold);
}

/* updateSingleAabb: with m_useContinuous (`continuous`) a dynamic body's AABB also covers its
 * predicted transform (predictIntegratedTransform with the damped velocities of this step). */
static inline BtgAabb btgStockAabb(BtgFloat4 pos, BtgFloat4 rot, BtgFloat4 linVel, BtgFloat4 angVel, BtgShape shape,
                                   uint flags, float threshold, float dt, int continuous)
{
    BtgAabb a = btgLeafShapeAabb(pos, rot, shape, flags, threshold);
    if (continuous && (flags & BTG_BODY_DYNAMIC) && !(flags & BTG_BODY_EXCLUDED) && shape.type != BTG_SHAPE_PLANE) {
        BtgFloat4 p = btgXyz(pos) + btgXyz(linVel) * dt;
        BtgFloat4 q = btgIntegrateRotation(rot, angVel, dt);
        BtgAabb b = btgBodyAabb(p, q, shape, flags, threshold);
        a.lo = btgMake4(btgMin(a.lo.x, b.lo.x), btgMin(a.lo.y, b.lo.y), btgMin(a.lo.z, b.lo.z), 0.0f);
        a.hi = btgMake4(btgMax(a.hi.x, b.hi.x), btgMax(a.hi.y, b.hi.y), btgMax(a.hi.z, b.hi.z), 0.0f);
    }
    return a;
}

/* btDbvtAabbMm::Contain and Intersect (touching counts). */
static inline int btgLeafContains(BtgAabb leaf, BtgAabb a)
{
    return leaf.lo.x <= a.lo.x && leaf.lo.y <= a.lo.y && leaf.lo.z <= a.lo.z && leaf.hi.x >= a.hi.x &&
           leaf.hi.y >= a.hi.y && leaf.hi.z >= a.hi.z;
}
static inline int btgLeafMeets(BtgAabb p, BtgAabb q)
{
    return p.lo.x <= q.hi.x && p.hi.x >= q.lo.x && p.lo.y <= q.hi.y && p.hi.y >= q.lo.y && p.lo.z <= q.hi.z &&
           p.hi.z >= q.lo.z;
}

/* setAabb on a leaf of the dynamic set (m_prediction 0): 1 when the leaf moved (docollide). */
static inline int btgLeafUpdate(BtgAabb* leaf, BtgAabb a)
{
    if (!btgLeafMeets(*leaf, a)) {
        *leaf = a;
        return 1;
    }
    if (btgLeafContains(*leaf, a)) return 0;
    BtgFloat4 m = btgMake4(BTG_DBVT_MARGIN, BTG_DBVT_MARGIN, BTG_DBVT_MARGIN, 0.0f);
    leaf->lo = a.lo - m;
    leaf->hi = a.hi + m;
    return 1;
}

/* A row's old and new leaf together: every pair stock's pass of setAabb calls can meet has
 * meeting boxes. */
static inline BtgAabb btgLeafUnion(BtgFloat4 lo, BtgFloat4 hi, BtgFloat4 oldLo, BtgFloat4 oldHi)
{
    BtgAabb u;
    u.lo = btgMake4(btgMin(lo.x, oldLo.x), btgMin(lo.y, oldLo.y), btgMin(lo.z, oldLo.z), 0.0f);
    u.hi = btgMake4(btgMax(hi.x, oldHi.x), btgMax(hi.y, oldHi.y), btgMax(hi.z, oldHi.z), 0.0f);
    return u;
}

/* Stock's pass updates the rows in order (the collision-object array's; rows keep it): a moved
 * leaf of the earlier row p is collided against q's leaf before q's update, a moved leaf of q
 * against p's new one; each overlap met counts towards m_newpairs and is added to the pair
 * cache. The pair's share of m_newpairs; *meets: the new leaves meet (the pair is in the list). */
static inline uint btgLeafJudge(BtgAabb newP, BtgAabb newQ, BtgAabb oldQ, uint movedP, uint movedQ, int* meets)
{
    *meets = btgLeafMeets(newP, newQ);
    uint share = 0u;
    if (movedP && btgLeafMeets(newP, oldQ)) ++share;
    if (movedQ && *meets) ++share;
    return share;
}

/* btHashedOverlappingPairCache::needsBroadphaseCollision with the rows' group and mask. */
static inline int btgLeafPairAllowed(BtgBodyProps a, BtgBodyProps b)
{
    if ((a.flags | b.flags) & BTG_BODY_EXCLUDED) return 0;
    return (a.group & b.mask) != 0 && (b.group & a.mask) != 0;
}

#ifdef __OPENCL_C_VERSION__
static inline uint btgFloatBits(float x) { return as_uint(x); }
#else
static inline uint btgFloatBits(float x)
{
    uint u;
    std::memcpy(&u, &x, sizeof(u));
    return u;
}
#endif

/* Sweep key of an x bound: the float's order as an unsigned integer, its top 16 bits (half the
 * sort's passes; a bucket is 1/128 of the value's binade). The sweep stops at the first leaf whose
 * lower bound's key passes the upper bound's: every later leaf's bound is past it too, so no
 * overlap is missed, and leaves of the same bucket are only tested more. 0xffff: no leaf. */
#define BTG_LEAF_SWEEP_BITS 16
static inline uint btgLeafSweepKey(float x)
{
    uint u = btgFloatBits(x);
    u = (u & 0x80000000u) ? ~u : (u | 0x80000000u);
    return u >> (32 - BTG_LEAF_SWEEP_BITS);
}

/* The sweep's (y, z) cells: an entry's key is its cell's hash (BTG_LEAF_CELL_BITS) above the
 * sweep key; all ones (a NaN bound's only) marks no entry. */
#define BTG_LEAF_CELL_BITS 12
#define BTG_LEAF_NO_ENTRY ((1u << (BTG_LEAF_CELL_BITS + BTG_LEAF_SWEEP_BITS)) - 1u)
static inline BtgInt4 btgLeafCell(BtgFloat4 p, float invCell)
{
    BtgInt4 c;
    c.x = 0;
    c.y = btgGridCoord(p.y, invCell);
    c.z = btgGridCoord(p.z, invCell);
    c.w = 0;
    return c;
}
static inline uint btgLeafCellHash(int y, int z) { return btgGridHash(0, y, z, (1u << BTG_LEAF_CELL_BITS) - 1u); }

static inline int btgLeafPairLess(BtgPair p, BtgPair q) { return p.a < q.a || (p.a == q.a && p.b < q.b); }

/* The first of pairs[0, n) (sorted by (a, b)) not below q. */
static inline int btgLeafLowerBound(BTG_CONST_GLOBAL BtgPair* pairs, int n, BtgPair q)
{
    int lo = 0, hi = n;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (btgLeafPairLess(pairs[mid], q)) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}
static inline int btgLeafPairAt(BTG_CONST_GLOBAL BtgPair* pairs, int n, int at, BtgPair q)
{
    return at < n && pairs[at].a == q.a && pairs[at].b == q.b;
}
/* Whether q is in pairs[0, n) (sorted by (a, b)). */
static inline int btgLeafPairIn(BTG_CONST_GLOBAL BtgPair* pairs, int n, BtgPair q)
{
    return btgLeafPairAt(pairs, n, btgLeafLowerBound(pairs, n, q), q);
}

#endif
