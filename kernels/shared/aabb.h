/* aabb.h — a body's world AABB, shared by kernels/update_aabbs.cl and its CPU reference.
 * Follows Bullet's btTransformAabb (centre + |R| * half extents) for hulls and
 * btSphereShape::getAabb (centre +- radius) for spheres, and Bullet's getAabbSlow (the support
 * along each world axis plus the margin) for cones and uniformly scaled shapes; planes and
 * excluded rows get an inverted box that overlaps nothing, so they never enter the grid. */
#ifndef BTG_AABB_H
#define BTG_AABB_H
#include "math.h"
#include "support.h"
#include "types.h"

/* Finite rather than infinite so that centre = (lo + hi) / 2 stays a number. */
#define BTG_AABB_HUGE 1e30f

typedef struct {
    BtgFloat4 lo; /* m; w 0 */
    BtgFloat4 hi; /* m; w 0 */
} BtgAabb;

static inline BtgAabb btgEmptyAabb(void)
{
    BtgAabb a;
    a.lo = btgMake4(BTG_AABB_HUGE, BTG_AABB_HUGE, BTG_AABB_HUGE, 0.0f);
    a.hi = btgMake4(-BTG_AABB_HUGE, -BTG_AABB_HUGE, -BTG_AABB_HUGE, 0.0f);
    return a;
}

/* World AABB of one body grown by `threshold` m on every side. */
static inline BtgAabb btgBodyAabb(BtgFloat4 pos, BtgFloat4 rot, BtgShape shape, uint flags, float threshold)
{
    if (shape.type == BTG_SHAPE_PLANE || (flags & BTG_BODY_EXCLUDED)) return btgEmptyAabb();
    BtgFloat4 centre;
    BtgFloat4 extent;
    const uint slow = BTG_CONVEX_FLAG_AABB_SUPPORT | BTG_CONVEX_FLAG_AABB_SLOW;
    if (shape.type == BTG_SHAPE_SPHERE) {
        /* A sphere's box does not turn with it: rotating the local box would inflate it. */
        centre = btgXyz(pos);
        extent = btgMake4(shape.param.x, shape.param.x, shape.param.x, 0.0f);
    } else if (shape.type == BTG_SHAPE_CONVEX && (shape.convexFlags & slow)) {
        /* getAabbSlow: per world axis, the support point along it and against it (these rows'
           supports read no vertex table), grown by the margin; a cone's own getAabbSlow takes
           the full support and then adds the margin once more, as Bullet does. */
        BtgMat3 m = btgQuatToMat3(rot);
        const int full = (shape.convexFlags & BTG_CONVEX_FLAG_AABB_SLOW) != 0u;
        const float margin = btgCoreMargin(shape);
        float lo[3], hi[3];
        for (int i = 0; i < 3; ++i) {
            BtgFloat4 e = btgZero4();
            btgSetComp(&e, i, 1.0f);
            BtgFloat4 d = btgMat3TMulVec(m, e);
            BtgFloat4 up = full ? btgSupportFull(shape, 0, d) : btgSupportCore(shape, 0, d);
            BtgFloat4 dn = full ? btgSupportFull(shape, 0, -d) : btgSupportCore(shape, 0, -d);
            hi[i] = btgComp(btgMat3MulVec(m, up), i) + margin;
            lo[i] = btgComp(btgMat3MulVec(m, dn), i) - margin;
        }
        BtgFloat4 l = btgMake4(lo[0], lo[1], lo[2], 0.0f), h = btgMake4(hi[0], hi[1], hi[2], 0.0f);
        centre = btgXyz(pos) + (l + h) * 0.5f;
        extent = (h - l) * 0.5f;
    } else {
        BtgFloat4 halfExt = btgXyz(shape.localAabbMax - shape.localAabbMin) * 0.5f;
        BtgFloat4 localCentre = btgXyz(shape.localAabbMax + shape.localAabbMin) * 0.5f;
        BtgMat3 m = btgQuatToMat3(rot);
        BtgFloat4 a0 = btgMake4(btgAbs(m.r0.x), btgAbs(m.r0.y), btgAbs(m.r0.z), 0.0f);
        BtgFloat4 a1 = btgMake4(btgAbs(m.r1.x), btgAbs(m.r1.y), btgAbs(m.r1.z), 0.0f);
        BtgFloat4 a2 = btgMake4(btgAbs(m.r2.x), btgAbs(m.r2.y), btgAbs(m.r2.z), 0.0f);
        centre = btgMat3MulVec(m, localCentre) + btgXyz(pos);
        extent = btgMake4(btgDot3(a0, halfExt), btgDot3(a1, halfExt), btgDot3(a2, halfExt), 0.0f);
    }
    BtgFloat4 grow = btgMake4(threshold, threshold, threshold, 0.0f);
    BtgAabb a;
    a.lo = centre - extent - grow;
    a.hi = centre + extent + grow;
    return a;
}

#endif
