/* aabb.h — a body's world AABB, shared by kernels/update_aabbs.cl and its CPU reference.
 * Follows Bullet's btTransformAabb (centre + |R| * half extents) for hulls and
 * btSphereShape::getAabb (centre +- radius) for spheres; planes and excluded rows get an
 * inverted box that overlaps nothing, so they never enter the grid. */
#ifndef BTG_AABB_H
#define BTG_AABB_H
#include "math.h"
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
    if (shape.type == BTG_SHAPE_SPHERE) {
        /* A sphere's box does not turn with it: rotating the local box would inflate it. */
        centre = btgXyz(pos);
        extent = btgMake4(shape.param.x, shape.param.x, shape.param.x, 0.0f);
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
