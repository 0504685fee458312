/* compound.h — compound shapes as collider rows: a pair side's shape and pose (a whole body, or
 * one leaf of its compound at body * leaf transform), and the expansion of a body pair that
 * holds a compound into its leaf pairs with stock btCompoundCollisionAlgorithm's culling (the
 * dynamic AABB tree's query in the compound's frame, then ProcessChildShape's world AABB test;
 * two compounds as btCompoundCompoundCollisionAlgorithm's tree-tree walk, or its base class's
 * nested walk where one has no tree). Shared by
 * expand_compounds, every narrowphase kernel and their CPU references.
 *
 * One deviation: stock grows neither test (m_closestPointDistanceThreshold is 0 in a dynamics
 * step) because its resting bodies sink a little, so their leaves' boxes overlap; btgpu's
 * speculative contacts rest a body at zero separation, where an ungrown test drops the leaf
 * pair every few steps and the body falls a step's worth onto it (measured: 2.8 mm for a
 * table). Both tests are grown by the pair's breaking threshold there (`speculative`, the soft
 * step), as the midphase grows its box for the same reason: a leaf within the threshold gets its
 * (speculative) points. The bullet mode, whose bodies rest as stock's, tests as stock does
 * (btgLeafTestGrowth): a grown test there found a kinematic arm's leaf a step before stock and
 * stopped a ball early. */
#ifndef BTG_COMPOUND_H
#define BTG_COMPOUND_H
#include "aabb.h"
#include "broadphase.h"
#include "narrowphase_common.h"

#define BTG_CHILD_TABLE BTG_CONST_GLOBAL BtgChild* children

/* The shape row of a pair's side (0: A, 1: B): the leaf's, or the body's own. */
static inline BtgShape btgPairSideShape(BtgPair p, int side, BTG_CONST_GLOBAL BtgBodyProps* props,
                                        BTG_CONST_GLOBAL BtgShape* shapes, BTG_CHILD_TABLE)
{
    const int body = side ? p.b : p.a, child = side ? p.childB : p.childA;
    if (child == BTG_WHOLE_BODY) return shapes[props[body].shape];
    BtgShape s = shapes[children[child - 1].shape];
    /* Stock's manifold of a child pair belongs to the two collision objects: its breaking
       threshold is the compound's own (btCollisionDispatcher::getNewManifold). */
    s.breakingThreshold = shapes[props[body].shape].breakingThreshold;
    return s;
}

/* The pair kind of a (possibly child) pair. */
static inline int btgPairKindOf(BtgPair p, BTG_CONST_GLOBAL BtgBodyProps* props, BTG_CONST_GLOBAL BtgShape* shapes,
                                BTG_CHILD_TABLE)
{
    return btgPairKind(btgPairSideShape(p, 0, props, shapes, children).type,
                       btgPairSideShape(p, 1, props, shapes, children).type);
}

/* Whether the GJK state the narrowphase left at pair p's slot is p's own of this substep (a kind
 * with a persistent manifold, p's bodies, a convex–concave pair's with the convex first): the
 * contact report and the callbacks' gather read it. */
static inline int btgHasPersistentState(BtgPair p, BtgPersistentManifold s, BTG_CONST_GLOBAL BtgBodyProps* props,
                                        BTG_CONST_GLOBAL BtgShape* shapes, BTG_CHILD_TABLE)
{
    const int kind = btgPairKindOf(p, props, shapes, children);
    return btgIsPersistentKind(kind) && s.kind == kind &&
           ((s.bodyA == p.a && s.bodyB == p.b) || (btgIsConcaveKind(kind) && s.bodyA == p.b && s.bodyB == p.a));
}

/* A leaf's world pose as a position and quaternion (Bullet's body * child transform). */
static inline void btgChildWorld(BtgFloat4 bodyPos, BtgFloat4 bodyRot, BtgChild c, BtgFloat4* pos, BtgFloat4* rot)
{
    *pos = btgXyz(bodyPos) + btgQuatRotate(bodyRot, c.pos);
    *rot = btgQuatMul(bodyRot, c.rot);
}

/* One side of a pair as the contact routines take it: the body row stays the body (manifolds
 * and contacts act on bodies), the pose and shape are the leaf's. */
static inline BtgCollider btgLoadPairCollider(BtgPair p, int side, BTG_CONST_GLOBAL BtgFloat4* pos,
                                              BTG_CONST_GLOBAL BtgFloat4* rot, BTG_CONST_GLOBAL BtgBodyProps* props,
                                              BTG_CONST_GLOBAL BtgShape* shapes, BTG_CHILD_TABLE)
{
    const int body = side ? p.b : p.a, child = side ? p.childB : p.childA;
    BtgCollider c = btgLoadCollider(body, pos, rot, props, shapes);
    if (child != BTG_WHOLE_BODY) {
        BtgFloat4 wp, wq;
        btgChildWorld(pos[body], rot[body], children[child - 1], &wp, &wq);
        c.pose.pos = wp;
        c.pose.rot = btgQuatToMat3(wq);
        c.shape = btgPairSideShape(p, side, props, shapes, children);
    }
    return c;
}

/* A child pair's manifold names each leaf by Bullet's child index (setShapeIdentifiersA/B(-1,
 * index)); the contact cache matches manifolds on these keys, so each leaf pair keeps its own. */
static inline BtgManifold btgWithChildKeys(BtgManifold m, BtgPair p, BTG_CHILD_TABLE)
{
    if (p.childA != BTG_WHOLE_BODY) {
        m.partIdA = BTG_NO_SUB_SHAPE;
        m.indexA = children[p.childA - 1].index;
    }
    if (p.childB != BTG_WHOLE_BODY) {
        m.partIdB = BTG_NO_SUB_SHAPE;
        m.indexB = children[p.childB - 1].index;
    }
    return m;
}

/* The key a pair's manifold is looked up by in the cache (its bodies and leaf keys). */
static inline BtgManifold btgPairKeyManifold(BtgPair p, BTG_CHILD_TABLE)
{
    return btgWithChildKeys(btgEmptyManifold(p.a, p.b), p, children);
}

/* A body's world AABB as Bullet's getAabb gives it, not grown; a plane's is all of space
 * (btStaticPlaneShape::getAabb). */
static inline BtgAabb btgGrown(BtgAabb a, float by)
{
    const BtgFloat4 g = btgMake4(by, by, by, 0.0f);
    a.lo = a.lo - g;
    a.hi = a.hi + g;
    return a;
}

/* How far the leaf culling grows its boxes: the pair's threshold where speculative (the
 * deviation above), else BTG_LEAF_TEST_SLACK, 0.1 mm: stock's exact boxes, but for the last
 * bits of their float arithmetic, which is not Bullet's operation for operation here (a table
 * standing exactly on the ground: stock's leg box reaches 1e-8 below the ground's top, btgpu's
 * stopped at it, and two legs' pairs were missing for the first steps). */
#define BTG_LEAF_TEST_SLACK 1e-4f
static inline float btgLeafTestGrowth(int speculative, BtgShape a, BtgShape b)
{
    return speculative ? btgPairThreshold(a, b) : BTG_LEAF_TEST_SLACK;
}

static inline BtgAabb btgStockAabb(BtgFloat4 pos, BtgFloat4 rot, BtgShape s)
{
    if (s.type == BTG_SHAPE_PLANE) {
        BtgAabb all;
        all.lo = btgMake4(-BTG_AABB_HUGE, -BTG_AABB_HUGE, -BTG_AABB_HUGE, 0.0f);
        all.hi = btgMake4(BTG_AABB_HUGE, BTG_AABB_HUGE, BTG_AABB_HUGE, 0.0f);
        return all;
    }
    return btgBodyAabb(pos, rot, s, 0u, 0.0f);
}

/* A box given in one frame, as an AABB in another (btTransformAabb with no margin): pos/rot
 * carry the box's frame into the other. */
static inline BtgAabb btgTransformBox(BtgFloat4 lo, BtgFloat4 hi, BtgFloat4 pos, BtgFloat4 rot)
{
    const BtgFloat4 halfExt = btgXyz(hi - lo) * 0.5f, centre = btgXyz(hi + lo) * 0.5f;
    const BtgMat3 m = btgQuatToMat3(rot);
    const BtgFloat4 a0 = btgMake4(btgAbs(m.r0.x), btgAbs(m.r0.y), btgAbs(m.r0.z), 0.0f);
    const BtgFloat4 a1 = btgMake4(btgAbs(m.r1.x), btgAbs(m.r1.y), btgAbs(m.r1.z), 0.0f);
    const BtgFloat4 a2 = btgMake4(btgAbs(m.r2.x), btgAbs(m.r2.y), btgAbs(m.r2.z), 0.0f);
    const BtgFloat4 c = btgMat3MulVec(m, centre) + btgXyz(pos);
    const BtgFloat4 e = btgMake4(btgDot3(a0, halfExt), btgDot3(a1, halfExt), btgDot3(a2, halfExt), 0.0f);
    BtgAabb out;
    out.lo = c - e;
    out.hi = c + e;
    return out;
}

/* Leaf pair (leaf rows ra of A, rb of B) of body pair p written to out[at] when it fits; 1. */
static inline uint btgEmitLeafPair(BtgPair p, int ra, int rb, BTG_GLOBAL BtgPair* out, uint at, uint capacity)
{
    if (out && at < capacity) {
        BtgPair q = p;
        q.childA = ra + 1;
        q.childB = rb + 1;
        out[at] = q;
    }
    return 1u;
}

/* Two compounds (btCompoundCompoundCollisionAlgorithm, both with trees and neither nested: the
 * CPU-path rules send the others away): leaf i of A and leaf j of B, in (i, j) order, when B's tree leaf carried
 * into A's frame overlaps A's (MycollideTT's MyIntersect, A being stock's body 0: the lower
 * row, as the pair cache orders proxies by creation) and their world AABBs overlap. */
static inline uint btgExpandCompoundCompound(BtgPair p, BtgShape sa, BtgShape sb, BTG_CONST_GLOBAL BtgFloat4* pos,
                                             BTG_CONST_GLOBAL BtgFloat4* rot, BTG_CONST_GLOBAL BtgShape* shapes,
                                             BTG_CHILD_TABLE, BTG_GLOBAL BtgPair* out, uint first, uint capacity,
                                             int speculative)
{
    const float t = btgLeafTestGrowth(speculative, sa, sb);
    const BtgFloat4 qa = rot[p.a], qb = rot[p.b];
    const BtgFloat4 relPos = btgQuatRotate(btgQuatConj(qa), btgXyz(pos[p.b] - pos[p.a]));
    const BtgFloat4 relRot = btgQuatMul(btgQuatConj(qa), qb);
    uint n = 0u;
    for (int i = 0; i < sa.numChildren; ++i) {
        const BtgChild ca = children[sa.firstChild + i];
        BtgFloat4 wpa, wqa;
        btgChildWorld(pos[p.a], qa, ca, &wpa, &wqa);
        const BtgAabb boxA = btgGrown(btgStockAabb(wpa, wqa, shapes[ca.shape]), t);
        BtgAabb treeA;
        treeA.lo = ca.treeAabbMin;
        treeA.hi = ca.treeAabbMax;
        treeA = btgGrown(treeA, t);
        for (int j = 0; j < sb.numChildren; ++j) {
            const BtgChild cb = children[sb.firstChild + j];
            const BtgAabb treeB = btgTransformBox(cb.treeAabbMin, cb.treeAabbMax, relPos, relRot);
            if (!btgAabbOverlap(treeA.lo, treeA.hi, treeB.lo, treeB.hi)) continue;
            BtgFloat4 wpb, wqb;
            btgChildWorld(pos[p.b], qb, cb, &wpb, &wqb);
            const BtgAabb boxB = btgStockAabb(wpb, wqb, shapes[cb.shape]);
            if (!btgAabbOverlap(boxA.lo, boxA.hi, boxB.lo, boxB.hi)) continue;
            n += btgEmitLeafPair(p, sa.firstChild + i, sb.firstChild + j, out, first + n, capacity);
        }
    }
    return n;
}

/* Whether leaf c of a compound (at body pose pos/rot) passes btCompoundLeafCallback's tests against
 * another collider: its holder's tree query with the other's box in the compound's frame
 * (otherLocal), then its world AABB against the other's (other, both boxes grown as above). */
static inline int btgLeafMeets(BtgChild c, BtgFloat4 pos, BtgFloat4 rot, BtgAabb otherLocal, BtgAabb other,
                               BTG_CONST_GLOBAL BtgShape* shapes, BtgAabb* leafBox)
{
    if (c.useTree && !btgAabbOverlap(c.treeAabbMin, c.treeAabbMax, otherLocal.lo, otherLocal.hi)) return 0;
    BtgFloat4 wp, wq;
    btgChildWorld(pos, rot, c, &wp, &wq);
    *leafBox = btgStockAabb(wp, wq, shapes[c.shape]);
    return btgAabbOverlap(leafBox->lo, leafBox->hi, other.lo, other.hi);
}

/* Two compounds of which one has no dynamic AABB tree (btCompoundShape(false); neither nested:
 * the CPU-path rules send those away): btCompoundCompoundCollisionAlgorithm then runs its base
 * btCompoundCollisionAlgorithm, whose child algorithm for leaf i of A (body 0) is a compound
 * algorithm over B's leaves against that leaf. So leaf i when it meets B's whole box, then leaf j
 * of B when it meets leaf i, in (i, j) order; the manifold is the innermost algorithm's, B's leaf
 * first (ManifoldSync::orient). */
static inline uint btgExpandCompoundNested(BtgPair p, BtgShape sa, BtgShape sb, BTG_CONST_GLOBAL BtgFloat4* pos,
                                           BTG_CONST_GLOBAL BtgFloat4* rot, BTG_CONST_GLOBAL BtgShape* shapes,
                                           BTG_CHILD_TABLE, BTG_GLOBAL BtgPair* out, uint first, uint capacity,
                                           int speculative)
{
    const float t = btgLeafTestGrowth(speculative, sa, sb);
    const BtgFloat4 qa = rot[p.a], qb = rot[p.b];
    const BtgAabb wholeB = btgGrown(btgStockAabb(pos[p.b], qb, sb), t);
    const BtgAabb bInA = btgGrown(btgStockAabb(btgQuatRotate(btgQuatConj(qa), btgXyz(pos[p.b] - pos[p.a])),
                                               btgQuatMul(btgQuatConj(qa), qb), sb),
                                  t);
    uint n = 0u;
    for (int i = 0; i < sa.numChildren; ++i) {
        const BtgChild ca = children[sa.firstChild + i];
        BtgAabb boxA;
        if (!btgLeafMeets(ca, pos[p.a], qa, bInA, wholeB, shapes, &boxA)) continue;
        /* Leaf i as the other collider of B's compound algorithm. */
        BtgFloat4 wpa, wqa;
        btgChildWorld(pos[p.a], qa, ca, &wpa, &wqa);
        const BtgAabb other = btgGrown(boxA, t);
        const BtgAabb aInB = btgGrown(btgStockAabb(btgQuatRotate(btgQuatConj(qb), btgXyz(wpa - pos[p.b])),
                                                   btgQuatMul(btgQuatConj(qb), wqa), shapes[ca.shape]),
                                      t);
        for (int j = 0; j < sb.numChildren; ++j) {
            BtgAabb boxB;
            if (!btgLeafMeets(children[sb.firstChild + j], pos[p.b], qb, aInB, other, shapes, &boxB)) continue;
            n += btgEmitLeafPair(p, sa.firstChild + i, sb.firstChild + j, out, first + n, capacity);
        }
    }
    return n;
}

/* A compound's own dynamic AABB tree (its leaves' holder is it: none is nested here). */
static inline int btgCompoundHasTree(BtgShape s, BTG_CHILD_TABLE)
{
    return s.numChildren == 0 || children[s.firstChild].useTree;
}

/* The leaf pairs of body pair p (a < b) with a compound side: those stock processes, in child
 * order. Writes them to out[first, capacity) when out is given; returns how many. A pair with
 * no compound is itself. speculative: the tests grown by the pair's threshold (the deviation
 * above: the soft step), else stock's. */
static inline uint btgExpandPair(BtgPair p, BTG_CONST_GLOBAL BtgFloat4* pos, BTG_CONST_GLOBAL BtgFloat4* rot,
                                 BTG_CONST_GLOBAL BtgBodyProps* props, BTG_CONST_GLOBAL BtgShape* shapes, BTG_CHILD_TABLE,
                                 BTG_GLOBAL BtgPair* out, uint first, uint capacity, int speculative)
{
    const BtgShape sa = shapes[props[p.a].shape], sb = shapes[props[p.b].shape];
    const int compoundIsA = sa.type == BTG_SHAPE_COMPOUND;
    if (!compoundIsA && sb.type != BTG_SHAPE_COMPOUND) {
        if (out && first < capacity) out[first] = p;
        return 1u;
    }
    if (compoundIsA && sb.type == BTG_SHAPE_COMPOUND) {
        if (btgCompoundHasTree(sa, children) && btgCompoundHasTree(sb, children))
            return btgExpandCompoundCompound(p, sa, sb, pos, rot, shapes, children, out, first, capacity, speculative);
        return btgExpandCompoundNested(p, sa, sb, pos, rot, shapes, children, out, first, capacity, speculative);
    }
    const int cb = compoundIsA ? p.a : p.b, ob = compoundIsA ? p.b : p.a;
    const BtgShape cs = compoundIsA ? sa : sb, os = compoundIsA ? sb : sa;
    /* The other body's boxes grown by the pair's threshold where speculative (the deviation above). */
    const float t = btgLeafTestGrowth(speculative, cs, os);
    const BtgAabb other = btgGrown(btgStockAabb(pos[ob], rot[ob], os), t);
    /* The other body in the compound's frame, for the tree's query (otherInCompoundSpace). */
    const BtgFloat4 cq = rot[cb];
    const BtgFloat4 relPos = btgQuatRotate(btgQuatConj(cq), btgXyz(pos[ob] - pos[cb]));
    const BtgFloat4 relRot = btgQuatMul(btgQuatConj(cq), rot[ob]);
    const BtgAabb otherLocal = btgGrown(btgStockAabb(relPos, relRot, os), t);
    uint n = 0u;
    for (int k = 0; k < cs.numChildren; ++k) {
        const int row = cs.firstChild + k;
        /* The leaf and each nested compound above it: all their levels' tests pass. */
        int keep = 1;
        for (int r = row; r >= 0 && keep; r = children[r].parent) {
            const BtgChild c = children[r];
            if (c.useTree) {
                BtgAabb inHolder = otherLocal;
                if (c.parent >= 0) {
                    /* The other body in the nested holder's frame. */
                    const BtgChild h = children[c.parent];
                    const BtgFloat4 hq = btgQuatMul(cq, h.rot);
                    const BtgFloat4 hp = btgXyz(pos[cb]) + btgQuatRotate(cq, h.pos);
                    inHolder = btgGrown(btgStockAabb(btgQuatRotate(btgQuatConj(hq), btgXyz(pos[ob] - hp)),
                                                     btgQuatMul(btgQuatConj(hq), rot[ob]), os),
                                        t);
                }
                keep = btgAabbOverlap(c.treeAabbMin, c.treeAabbMax, inHolder.lo, inHolder.hi);
            }
            if (keep) {
                BtgFloat4 wp, wq;
                btgChildWorld(pos[cb], cq, c, &wp, &wq);
                const BtgAabb box = btgStockAabb(wp, wq, shapes[c.shape]);
                keep = btgAabbOverlap(box.lo, box.hi, other.lo, other.hi);
            }
        }
        if (!keep) continue;
        if (out && first + n < capacity) {
            BtgPair q = p;
            if (compoundIsA) q.childA = row + 1;
            else q.childB = row + 1;
            out[first + n] = q;
        }
        ++n;
    }
    return n;
}

#endif
