/* soft_afresh.h — which of the GJK program's pairs the soft step collides afresh each substep,
 * keeping no manifold (btgSoftCollidesAfresh), and how (btgCollideSoftAfresh): two spheres,
 * a box or hull on a plane (simple_contacts.h), a capsule or cylinder on a box or a plane
 * (round_contacts.h). The bullet mode keeps stock's persistent manifold for all of them. */
#ifndef BTG_SOFT_AFRESH_H
#define BTG_SOFT_AFRESH_H
#include "simple_contacts.h"
#include "round_contacts.h"

/* The kinds of BTG_SOFT_COLLIDES_AFRESH; a plane with a point-cloud convex row (a hull without
 * polyhedral features, a convex triangle mesh); a capsule or cylinder on a box or a plane (kinds
 * CONVEX_BOX and PLANE_CONVEX, which keep their state buffers for the other convex shapes). */
static inline int btgSoftCollidesAfresh(int kind, BtgShape a, BtgShape b)
{
    if (BTG_SOFT_COLLIDES_AFRESH(kind)) return 1;
    if ((kind == BTG_PAIR_CONVEX_BOX || kind == BTG_PAIR_PLANE_CONVEX) && btgRoundOnFace(a, b)) return 1;
    return kind == BTG_PAIR_PLANE_CONVEX &&
           ((a.type == BTG_SHAPE_CONVEX && a.convexType == BTG_CONVEX_POINTS) ||
            (b.type == BTG_SHAPE_CONVEX && b.convexType == BTG_CONVEX_POINTS));
}

/* Those of them collide_fresh takes: all but a capsule or cylinder on a box, whose face comes from GJK
 * (collide_persistent's kernel has its registers; collide_fresh keeps to the closed forms). */
static inline int btgSoftFreshKernelPair(int kind, BtgShape a, BtgShape b)
{
    return kind != BTG_PAIR_CONVEX_BOX && btgSoftCollidesAfresh(kind, a, b);
}

/* collide_fresh's collision of its pairs (btgSoftFreshKernelPair): btgCollideSoftAfresh's for
 * them, with no GJK in its code (a round body there lies on a plane). */
static inline BtgManifold btgCollideSoftFresh(BtgCollider a, BtgCollider b, BTG_SHAPE_TABLES, float threshold)
{
    if (a.shape.type == BTG_SHAPE_SPHERE && b.shape.type == BTG_SHAPE_SPHERE)
        return btgCollideSphereSphere(a, b, verts, faces, indices, edges, threshold);
    if (btgRoundOnFace(a.shape, b.shape)) return btgCollideRoundOnPlane(a, b, threshold);
    return btgCollideHullPlane(a, b, verts, faces, indices, edges, threshold);
}

/* The soft step's fresh collision of the pairs btgSoftCollidesAfresh names. */
static inline BtgManifold btgCollideSoftAfresh(BtgCollider a, BtgCollider b, BTG_SHAPE_TABLES, float threshold)
{
    if (a.shape.type == BTG_SHAPE_SPHERE && b.shape.type == BTG_SHAPE_SPHERE)
        return btgCollideSphereSphere(a, b, verts, faces, indices, edges, threshold);
    if (btgRoundOnFace(a.shape, b.shape)) return btgCollideRoundOnFace(a, b, verts, threshold);
    return btgCollideHullPlane(a, b, verts, faces, indices, edges, threshold);
}

#endif
