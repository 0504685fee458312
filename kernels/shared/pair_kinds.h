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
 * plus its Stage (src/world/plan.h, kNarrowphasePrograms in plan.cpp). */
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
#define BTG_PAIR_SPHERE_MESH 6 /* the mesh kinds are consecutive: the midphase walks their range */
#define BTG_PAIR_HULL_MESH 7
#define BTG_PAIR_SPHERE_HEIGHTFIELD 8
#define BTG_PAIR_HULL_HEIGHTFIELD 9
#define BTG_NUM_PAIR_KINDS 10
/* Convex against a concave shape (mesh or heightfield): the kinds the midphase walks. */
#define BTG_FIRST_MESH_PAIR_KIND BTG_PAIR_SPHERE_MESH
#define BTG_LAST_MESH_PAIR_KIND BTG_PAIR_HULL_HEIGHTFIELD

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
    X(narrowphase, BTG_PAIR_SPHERE_SPHERE, BTG_SHAPE_SPHERE, BTG_SHAPE_SPHERE, btgCollideSphereSphere,         \
      collide_sphere_sphere)                                                                                   \
    X(narrowphase, BTG_PAIR_SPHERE_HULL, BTG_SHAPE_SPHERE, BTG_SHAPE_HULL, btgCollideSphereHull,               \
      collide_sphere_hull)                                                                                     \
    X(narrowphase, BTG_PAIR_SPHERE_PLANE, BTG_SHAPE_SPHERE, BTG_SHAPE_PLANE, btgCollideSpherePlane,            \
      collide_sphere_plane)                                                                                    \
    X(narrowphase, BTG_PAIR_HULL_PLANE, BTG_SHAPE_HULL, BTG_SHAPE_PLANE, btgCollideHullPlane, collide_hull_plane)
#define BTG_PAIR_KINDS_NARROWPHASE_SAT(X) \
    X(narrowphase_sat, BTG_PAIR_HULL_HULL, BTG_SHAPE_HULL, BTG_SHAPE_HULL, btgCollideHullHull, collide_hull_hull)

/* Convex against mesh: the midphase (kernels/midphase.cl) splits each pair into (convex,
 * triangle) sub-pairs; a row's routine takes one of them (BTG_TRIANGLE_ROUTINE in
 * triangle_contacts.h: the convex, the mesh, the triangle's mesh-local vertices) and its
 * kernel strides over the sub-pairs of its kind. */
#define BTG_PAIR_KINDS_NARROWPHASE_MESH(X)                                                                    \
    X(narrowphase_mesh, BTG_PAIR_SPHERE_MESH, BTG_SHAPE_SPHERE, BTG_SHAPE_MESH, btgCollideSphereTriangle,     \
      collide_sphere_triangles)                                                                               \
    X(narrowphase_mesh, BTG_PAIR_HULL_MESH, BTG_SHAPE_HULL, BTG_SHAPE_MESH, btgCollideHullTriangle,           \
      collide_hull_triangles)                                                                                 \
    X(narrowphase_mesh, BTG_PAIR_SPHERE_HEIGHTFIELD, BTG_SHAPE_SPHERE, BTG_SHAPE_HEIGHTFIELD,                 \
      btgCollideSphereTriangle, collide_sphere_heightfield)                                                   \
    X(narrowphase_mesh, BTG_PAIR_HULL_HEIGHTFIELD, BTG_SHAPE_HULL, BTG_SHAPE_HEIGHTFIELD,                     \
      btgCollideHullTriangle, collide_hull_heightfield)

/* The pairs of two convex shapes (one routine call a pair), and the whole table, program by
 * program in launch order. */
#define BTG_PAIR_KINDS_CONVEX(X) BTG_PAIR_KINDS_NARROWPHASE(X) BTG_PAIR_KINDS_NARROWPHASE_SAT(X)
#define BTG_PAIR_KINDS(X) BTG_PAIR_KINDS_CONVEX(X) BTG_PAIR_KINDS_NARROWPHASE_MESH(X)

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

#endif
