/* support.h — support functions of every convex shape row, as Bullet 3.24 defines them
 * (localGetSupportVertexWithoutMarginNonVirtual and the shapes' own localGetSupportingVertex):
 * the "core" point of a shape farthest along a shape-local direction, and the margin GJK adds
 * around the core. Bullet's GJK runs on the cores and adds the margins afterwards; its EPA uses
 * the full shape (core + margin along the unit direction: localGetSupportVertexNonVirtual), its
 * convex-plane algorithm the shape's own localGetSupportingVertex (the same but for boxes). */
#ifndef BTG_SUPPORT_H
#define BTG_SUPPORT_H
#include "math.h"
#include "types.h"

#define BTG_SUPPORT_EPSILON 1.1920929e-07f /* Bullet's SIMD_EPSILON (float) */

static inline float btgComp(BtgFloat4 v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }
static inline void btgSetComp(BtgFloat4* v, int i, float x)
{
    if (i == 0) v->x = x;
    else if (i == 1) v->y = x;
    else v->z = x;
}

/* Bullet's normalisation for support directions: a (near) zero direction becomes `fallback`. */
static inline BtgFloat4 btgSupportDir(BtgFloat4 d, float minLen2, BtgFloat4 fallback)
{
    float l2 = btgDot3(d, d);
    if (l2 < minLen2) return fallback;
    return btgXyz(d) * (1.0f / btgSqrt(l2));
}

/* btCylinderShape{X,,Z}::localGetSupportingVertexWithoutMargin: the radius is the half extent
 * on the first radial axis Bullet names for the variant. */
static inline BtgFloat4 btgCylinderSupport(BtgFloat4 h, int up, BtgFloat4 v)
{
    const int xx = up == 0 ? 1 : 0;
    const int zz = up == 2 ? 1 : 2;
    const float radius = btgComp(h, xx), halfHeight = btgComp(h, up);
    BtgFloat4 t = btgZero4();
    const float vx = btgComp(v, xx), vz = btgComp(v, zz);
    const float s = btgSqrt(vx * vx + vz * vz);
    if (s != 0.0f) {
        const float d = radius / s;
        btgSetComp(&t, xx, vx * d);
        btgSetComp(&t, zz, vz * d);
    } else {
        btgSetComp(&t, xx, radius);
    }
    btgSetComp(&t, up, btgComp(v, up) < 0.0f ? -halfHeight : halfHeight);
    return t;
}

/* btConeShape::coneLocalSupport (the cone's own support has no margin inside it: Bullet's cone
 * is its nominal cone grown by the margin). */
static inline BtgFloat4 btgConeSupport(float radius, float height, float sinAngle, int up, BtgFloat4 v)
{
    const int r1 = up == 0 ? 1 : 0;
    const int r2 = up == 2 ? 1 : 2;
    const float halfHeight = 0.5f * height;
    BtgFloat4 t = btgZero4();
    if (btgComp(v, up) > btgLength3(v) * sinAngle) {
        btgSetComp(&t, up, halfHeight);
        return t;
    }
    const float v1 = btgComp(v, r1), v2 = btgComp(v, r2);
    const float s = btgSqrt(v1 * v1 + v2 * v2);
    btgSetComp(&t, up, -halfHeight);
    if (s > BTG_SUPPORT_EPSILON) {
        const float d = radius / s;
        btgSetComp(&t, r1, v1 * d);
        btgSetComp(&t, r2, v2 * d);
    }
    return t;
}

/* The margin GJK grows the core by (Bullet's getMarginNonVirtual). */
static inline float btgCoreMargin(BtgShape s)
{
    if (s.type == BTG_SHAPE_SPHERE) return s.param.x;
    if (s.convexType == BTG_CONVEX_BOX) return s.param.w;
    return s.margin;
}

/* The core point farthest along shape-local direction d (need not be unit). */
static inline BtgFloat4 btgSupportCore(BtgShape s, BTG_CONST_GLOBAL BtgFloat4* verts, BtgFloat4 d)
{
    if (s.type == BTG_SHAPE_SPHERE || s.type == BTG_SHAPE_PLANE) return btgZero4();
    switch (s.convexType) {
        case BTG_CONVEX_BOX: {
            BtgFloat4 h = btgXyz(s.param) - btgMake4(s.param.w, s.param.w, s.param.w, 0.0f);
            return btgMake4(d.x >= 0.0f ? h.x : -h.x, d.y >= 0.0f ? h.y : -h.y, d.z >= 0.0f ? h.z : -h.z, 0.0f);
        }
        case BTG_CONVEX_CAPSULE: {
            /* the two segment ends; +half height on a tie, as Bullet's strict comparison */
            BtgFloat4 v = btgSupportDir(d, BTG_SUPPORT_EPSILON * BTG_SUPPORT_EPSILON, btgMake4(1.0f, 0.0f, 0.0f, 0.0f));
            BtgFloat4 t = btgZero4();
            const float h = s.param.y;
            btgSetComp(&t, s.upAxis, btgComp(v, s.upAxis) * -h > btgComp(v, s.upAxis) * h ? -h : h);
            return t;
        }
        case BTG_CONVEX_CYLINDER: return btgCylinderSupport(s.param, s.upAxis, d);
        case BTG_CONVEX_CONE: return btgConeSupport(s.param.x, s.param.y, s.param.z, s.upAxis, d);
        case BTG_CONVEX_SPHERE: return btgZero4();
        case BTG_CONVEX_TRIANGLE: {
            /* btTriangleShape: the first vertex of the largest dot (btVector3::maxAxis on ties) */
            const float d0 = btgDot3(d, s.localAabbMin), d1 = btgDot3(d, s.localAabbMax), d2 = btgDot3(d, s.param);
            const int i = d0 < d1 ? (d1 < d2 ? 2 : 1) : (d0 < d2 ? 2 : 0);
            return btgXyz(i == 0 ? s.localAabbMin : (i == 1 ? s.localAabbMax : s.param));
        }
        case BTG_CONVEX_SPHERES: {
            /* btMultiSphereShape: centre * scaling + dir * scaling * radius - dir * margin */
            BtgFloat4 v = btgSupportDir(d, BTG_SUPPORT_EPSILON * BTG_SUPPORT_EPSILON, btgMake4(1.0f, 0.0f, 0.0f, 0.0f));
            BtgFloat4 scale = btgXyz(s.param);
            BtgFloat4 best = btgZero4();
            float bestDot = -3.0e38f;
            for (int i = 0; i < s.numVertices; ++i) {
                BtgFloat4 c = verts[s.firstVertex + i];
                BtgFloat4 t = btgXyz(c) * scale + (v * scale) * c.w - v * s.margin;
                float dot = btgDot3(v, t);
                if (dot > bestDot) {
                    bestDot = dot;
                    best = btgXyz(t);
                }
            }
            return best;
        }
        default: {
            /* hull vertices or a point set: the first of the farthest */
            BtgFloat4 best = btgZero4();
            float bestDot = -3.0e38f;
            for (int i = 0; i < s.numVertices; ++i) {
                BtgFloat4 p = btgXyz(verts[s.firstVertex + i]);
                float dot = btgDot3(d, p);
                if (dot > bestDot) {
                    bestDot = dot;
                    best = p;
                }
            }
            return best;
        }
    }
}

/* The full shape's support: the core grown by the margin along the unit direction
 * (btConvexInternalShape::localGetSupportingVertex: a zero direction counts as (-1,-1,-1)). */
static inline BtgFloat4 btgSupportFull(BtgShape s, BTG_CONST_GLOBAL BtgFloat4* verts, BtgFloat4 d)
{
    BtgFloat4 core = btgSupportCore(s, verts, d);
    const float m = btgCoreMargin(s);
    if (m == 0.0f) return core;
    BtgFloat4 n = btgSupportDir(d, BTG_SUPPORT_EPSILON * BTG_SUPPORT_EPSILON, btgMake4(-1.0f, -1.0f, -1.0f, 0.0f));
    if (btgDot3(d, d) < BTG_SUPPORT_EPSILON * BTG_SUPPORT_EPSILON) n = btgNormalize3(n);
    return core + n * m;
}

/* The support the convex-plane algorithm reads (the shape's virtual localGetSupportingVertex):
 * the full support, but a box's is its sharp corner (btBoxShape overrides it), which a
 * uniformly scaled box inherits. */
static inline BtgFloat4 btgSupportForPlane(BtgShape s, BTG_CONST_GLOBAL BtgFloat4* verts, BtgFloat4 d)
{
    if (s.convexType == BTG_CONVEX_BOX)
        return btgMake4(d.x >= 0.0f ? s.param.x : -s.param.x, d.y >= 0.0f ? s.param.y : -s.param.y,
                        d.z >= 0.0f ? s.param.z : -s.param.z, 0.0f);
    return btgSupportFull(s, verts, d);
}

#endif
