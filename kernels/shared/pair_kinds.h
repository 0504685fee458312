/* pair_kinds.h — the pair-kind table: every (shape kind, shape kind) pair the narrowphase
 * handles, listed once with its kind id, its contact routine, its kernel and the program that
 * holds the kernel (Box2D v3's s_registers[type][type], Jolt's sCollideShape[sub][sub]). The
 * plan (src/world/plan.cpp) reads it to know which kinds a scene has, the launcher
 * (src/stages/narrowphase.cpp) to launch their kernels, the CPU reference to dispatch, and
 * the kernel files expand their own rows into kernels, so nothing else names a pair kind.
 *
 * Adding a shape kind: give it a BTG_SHAPE_* id (types.h, below BTG_NUM_SHAPE_KINDS), write
 * its routines (one per shape it meets) with the signature of BTG_COLLIDE_ROUTINE below, and
 * add one row per pair to the sub-table of the program that includes the routines. A new
 * program is a kernels/<program>.cl that includes its routines and expands its sub-table,
 * plus its Stage (src/world/plan.h, kNarrowphasePrograms in plan.cpp). A convex shape known
 * only by its support function needs no new kind: it is a BTG_SHAPE_CONVEX row with a new
 * BTG_CONVEX_* support function (support.h). */
#ifndef BTG_PAIR_KINDS_H
#define BTG_PAIR_KINDS_H
#include "types.h"

/* Pair kind ids. The id is also the pair's place in the kind-grouped order (find_pairs), so
 * kernels run in this order over ranges in this order. 0: a pair no routine takes (two
 * planes: never produced by the broadphase, both are static). */
#define BTG_PAIR_NONE 0
#define BTG_PAIR_SPHERE_SPHERE 1
#define BTG_PAIR_SPHERE_HULL 2
#define BTG_PAIR_SPHERE_PLANE 3
#define BTG_PAIR_HULL_PLANE 4
#define BTG_PAIR_HULL_HULL 5
#define BTG_PAIR_SPHERE_CONVEX 6
#define BTG_PAIR_HULL_CONVEX 7
#define BTG_PAIR_PLANE_CONVEX 8
#define BTG_PAIR_CONVEX_CONVEX 9
#define BTG_PAIR_SPHERE_BOX 10
#define BTG_PAIR_HULL_BOX 11
#define BTG_PAIR_PLANE_BOX 12
#define BTG_PAIR_CONVEX_BOX 13
#define BTG_PAIR_BOX_BOX 14
#define BTG_PAIR_SPHERE_MESH 15 /* the mesh kinds are consecutive: the midphase walks their range */
#define BTG_PAIR_HULL_MESH 16
#define BTG_PAIR_BOX_MESH 17
#define BTG_PAIR_SPHERE_HEIGHTFIELD 18
#define BTG_PAIR_HULL_HEIGHTFIELD 19
#define BTG_PAIR_BOX_HEIGHTFIELD 20
#define BTG_PAIR_CONVEX_MESH 21
#define BTG_PAIR_CONVEX_HEIGHTFIELD 22
#define BTG_NUM_PAIR_KINDS 23
/* Convex against a concave shape (mesh or heightfield): the kinds the midphase walks. */
#define BTG_FIRST_MESH_PAIR_KIND BTG_PAIR_SPHERE_MESH
#define BTG_LAST_MESH_PAIR_KIND BTG_PAIR_CONVEX_HEIGHTFIELD

/* The pairs grouped by kind (find_pairs): kindOrder lists the pair slots ordered by (kind, a, b),
 * and kind k's pairs are kindOrder[kindRanges[BTG_KIND_RANGE_START(k)], kindRanges[BTG_KIND_RANGE_END(k)]). */
#define BTG_KIND_RANGE_START(kind) (2 * (kind))
#define BTG_KIND_RANGE_END(kind) (2 * (kind) + 1)
#define BTG_KIND_RANGES_SIZE (2 * BTG_NUM_PAIR_KINDS)

/* The sub-tables, one per program. Row: X(program, kind, shape A, shape B, routine, kernel),
 * shape A <= shape B. A routine takes the pair's two colliders in the pair's own order
 * (A = pair.a, whichever shape that is), the shape tables and the pair's breaking threshold,
 * and returns the pair's manifold (BTG_COLLIDE_ROUTINE in narrowphase_common.h). */
#define BTG_PAIR_KINDS_NARROWPHASE(X)                                                                          \
    X(narrowphase, BTG_PAIR_SPHERE_HULL, BTG_SHAPE_SPHERE, BTG_SHAPE_HULL, btgCollideSphereHull,               \
      collide_sphere_hull)                                                                                     \
    X(narrowphase, BTG_PAIR_SPHERE_PLANE, BTG_SHAPE_SPHERE, BTG_SHAPE_PLANE, btgCollideSpherePlane,            \
      collide_sphere_plane)                                                                                    \
    X(narrowphase, BTG_PAIR_SPHERE_BOX, BTG_SHAPE_SPHERE, BTG_SHAPE_BOX, btgCollideSphereHull, collide_sphere_box)
/* Two boxes: stock's btBoxBoxDetector points into a persistent manifold (box_box.h); like the
 * GJK program's kinds, their kernels read and write the manifold each pair kept. */
#define BTG_PAIR_KINDS_NARROWPHASE_SAT(X) \
    X(narrowphase_sat, BTG_PAIR_BOX_BOX, BTG_SHAPE_BOX, BTG_SHAPE_BOX, btgCollideBoxBox, collide_box_box)
/* The pairs stock collides by GJK/EPA (btConvexConvexAlgorithm) or by the plane's support point
 * (btConvexPlaneCollisionAlgorithm, boxes and hulls included): one point a substep into a
 * persistent manifold (persistent_manifold.h); two hulls with polyhedral features add their
 * clipped faces after the GJK point (polyhedral_contacts.h). Their kernels also read and write
 * the manifold each pair kept (narrowphase_gjk.cl); the routine is the first step of a new pair.
 * Two spheres are here for the manifold's point identities (the callbacks'): their step holds
 * only btSphereSphereCollisionAlgorithm's closed-form point, made while they touch
 * (btgSpherePairPoint), since Bullet 3.24 clears that manifold every step. The soft step collides the kinds
 * of BTG_SOFT_COLLIDES_AFRESH afresh (btgCollideSoftAfresh) and keeps nothing for them. */
#define BTG_PAIR_KINDS_NARROWPHASE_GJK(X)                                                                               \
    X(narrowphase_gjk, BTG_PAIR_SPHERE_SPHERE, BTG_SHAPE_SPHERE, BTG_SHAPE_SPHERE, btgCollideGjk, collide_sphere_sphere) \
    X(narrowphase_gjk, BTG_PAIR_SPHERE_CONVEX, BTG_SHAPE_SPHERE, BTG_SHAPE_CONVEX, btgCollideGjk, collide_sphere_convex) \
    X(narrowphase_gjk, BTG_PAIR_HULL_CONVEX, BTG_SHAPE_HULL, BTG_SHAPE_CONVEX, btgCollideGjk, collide_hull_convex)       \
    X(narrowphase_gjk, BTG_PAIR_PLANE_CONVEX, BTG_SHAPE_PLANE, BTG_SHAPE_CONVEX, btgCollideGjk, collide_plane_convex)    \
    X(narrowphase_gjk, BTG_PAIR_CONVEX_CONVEX, BTG_SHAPE_CONVEX, BTG_SHAPE_CONVEX, btgCollideGjk, collide_convex_convex) \
    X(narrowphase_gjk, BTG_PAIR_HULL_HULL, BTG_SHAPE_HULL, BTG_SHAPE_HULL, btgCollideGjk, collide_hull_hull)             \
    X(narrowphase_gjk, BTG_PAIR_HULL_PLANE, BTG_SHAPE_HULL, BTG_SHAPE_PLANE, btgCollideGjk, collide_hull_plane)          \
    X(narrowphase_gjk, BTG_PAIR_HULL_BOX, BTG_SHAPE_HULL, BTG_SHAPE_BOX, btgCollideGjk, collide_hull_box)                \
    X(narrowphase_gjk, BTG_PAIR_PLANE_BOX, BTG_SHAPE_PLANE, BTG_SHAPE_BOX, btgCollideGjk, collide_plane_box)             \
    X(narrowphase_gjk, BTG_PAIR_CONVEX_BOX, BTG_SHAPE_CONVEX, BTG_SHAPE_BOX, btgCollideGjk, collide_convex_box)

/* The GJK program's kinds the soft step collides afresh each substep, keeping no manifold: two
 * spheres (their closed form, with speculative points) and a box or hull on a plane (every
 * vertex within the threshold, reduced to four: a box dropped flat on a btStaticPlaneShape meets
 * it with its face, where the one support point a step of stock's convex–plane algorithm lands
 * it on a corner and spins it). A hull without polyhedral features on a plane (kind
 * PLANE_CONVEX, a row of points) is collided so too, pair by pair (btgSoftCollidesAfresh,
 * simple_contacts.h); its kind keeps its state buffers for the curved shapes it also holds. */
#define BTG_SOFT_COLLIDES_AFRESH(kind) \
    ((kind) == BTG_PAIR_SPHERE_SPHERE || (kind) == BTG_PAIR_HULL_PLANE || (kind) == BTG_PAIR_PLANE_BOX)

/* Convex against mesh: the midphase (kernels/midphase.cl) splits each pair into (convex,
 * triangle) sub-pairs; a row's routine takes one of them (BTG_TRIANGLE_ROUTINE in
 * triangle_contacts.h: the convex, the mesh, the triangle's mesh-local vertices) and its
 * kernel strides over the sub-pairs of its kind. Boxes and hulls (a box's row holds its hull)
 * take the same routine; convex shapes known only by their support function take GJK against
 * the triangle (btgCollideConvexTriangleFresh: stock's one point per triangle per step, but a
 * capsule or cylinder lying on the triangle laid on its face). The mesh
 * bullet mode takes one point per triangle for every row (btgCollideTrianglePoint: stock's
 * algorithms) into the pair's persistent manifold (concave_manifold.h); the rows' routines
 * clip each triangle for the soft step, whose pairs keep nothing across steps. */
#define BTG_PAIR_KINDS_NARROWPHASE_MESH(X)                                                                    \
    X(narrowphase_mesh, BTG_PAIR_SPHERE_MESH, BTG_SHAPE_SPHERE, BTG_SHAPE_MESH, btgCollideSphereTriangle,     \
      collide_sphere_triangles)                                                                               \
    X(narrowphase_mesh, BTG_PAIR_HULL_MESH, BTG_SHAPE_HULL, BTG_SHAPE_MESH, btgCollideHullTriangle,           \
      collide_hull_triangles)                                                                                 \
    X(narrowphase_mesh, BTG_PAIR_BOX_MESH, BTG_SHAPE_BOX, BTG_SHAPE_MESH, btgCollideHullTriangle,             \
      collide_box_triangles)                                                                                  \
    X(narrowphase_mesh, BTG_PAIR_SPHERE_HEIGHTFIELD, BTG_SHAPE_SPHERE, BTG_SHAPE_HEIGHTFIELD,                 \
      btgCollideSphereTriangle, collide_sphere_heightfield)                                                   \
    X(narrowphase_mesh, BTG_PAIR_HULL_HEIGHTFIELD, BTG_SHAPE_HULL, BTG_SHAPE_HEIGHTFIELD,                     \
      btgCollideHullTriangle, collide_hull_heightfield)                                                       \
    X(narrowphase_mesh, BTG_PAIR_BOX_HEIGHTFIELD, BTG_SHAPE_BOX, BTG_SHAPE_HEIGHTFIELD,                       \
      btgCollideHullTriangle, collide_box_heightfield)                                                        \
    X(narrowphase_mesh, BTG_PAIR_CONVEX_MESH, BTG_SHAPE_CONVEX, BTG_SHAPE_MESH, btgCollideConvexTriangleFresh, \
      collide_convex_triangles)                                                                               \
    X(narrowphase_mesh, BTG_PAIR_CONVEX_HEIGHTFIELD, BTG_SHAPE_CONVEX, BTG_SHAPE_HEIGHTFIELD,                 \
      btgCollideConvexTriangleFresh, collide_convex_heightfield)

/* The pairs of two convex shapes one routine call makes at once (the GJK program's kernels
 * carry their persistent manifolds themselves), and the whole table, program by program in
 * launch order. */
#define BTG_PAIR_KINDS_CONVEX(X) BTG_PAIR_KINDS_NARROWPHASE(X) BTG_PAIR_KINDS_NARROWPHASE_SAT(X)
#define BTG_PAIR_KINDS(X) \
    BTG_PAIR_KINDS_CONVEX(X) BTG_PAIR_KINDS_NARROWPHASE_GJK(X) BTG_PAIR_KINDS_NARROWPHASE_MESH(X)

/* Kind of a pair of shape kinds, in either order; BTG_PAIR_NONE when no row takes it. */
#define BTG_PAIR_KIND_IF_ROW(program, kind, shapeA, shapeB, routine, kernel) \
    if (lo == (shapeA) && hi == (shapeB)) return (kind);
static inline int btgPairKind(int ta, int tb)
{
    int lo = ta < tb ? ta : tb, hi = ta < tb ? tb : ta;
    BTG_PAIR_KINDS(BTG_PAIR_KIND_IF_ROW)
    return BTG_PAIR_NONE;
}
#undef BTG_PAIR_KIND_IF_ROW

/* Whether a kind's pairs keep a persistent manifold (the box and GJK programs'; the mesh
 * program's in the bullet mode, whose manifold is kept with the convex as A). */
#define BTG_PAIR_KIND_CASE(program, kind, shapeA, shapeB, routine, kernel) case (kind):
static inline int btgIsPersistentKind(int kind)
{
    switch (kind) {
        BTG_PAIR_KINDS_NARROWPHASE_SAT(BTG_PAIR_KIND_CASE)
        BTG_PAIR_KINDS_NARROWPHASE_GJK(BTG_PAIR_KIND_CASE)
        BTG_PAIR_KINDS_NARROWPHASE_MESH(BTG_PAIR_KIND_CASE)
        return 1;
        default: return 0;
    }
}
#undef BTG_PAIR_KIND_CASE

/* Whether a kind is a convex against a mesh or heightfield. */
static inline int btgIsConcaveKind(int kind) { return kind >= BTG_FIRST_MESH_PAIR_KIND && kind <= BTG_LAST_MESH_PAIR_KIND; }

#endif
