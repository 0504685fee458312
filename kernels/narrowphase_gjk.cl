/* narrowphase_gjk.cl — Stage: narrowphase_gjk, the pairs with a convex shape known by its
 * support function (capsule, cylinder, cone, multi-sphere, convex triangle mesh, uniformly
 * scaled convex) against any convex or a plane, and two spheres: the one point Bullet's algorithm adds a step
 * (shared/gjk.h) into the pair's persistent manifold (shared/persistent_manifold.h); and,
 * after the solve, store_persistent_manifolds keeps those manifolds for the next substep.
 * Launch: collide_persistent, one kernel for every kind of the sub-table, any number of work-items
 * (in the soft step also collide_fresh, the same way, for the pairs it collides afresh),
 * striding over the kinds' ranges of the kind-grouped pairs laid end to end;
 * store_persistent_manifolds one work-item per contact slot.
 * Reads pairs, kindOrder, kindRanges, pos, rot, props, shapes, hull vertices/faces/indices, counters
 * [kPrevContactCount], contactCache (to find a pair's previous manifold), gjkCache.
 * Writes manifolds[slot], pairManifolds[slot] and gjkPairState[slot] of the kind's pairs;
 * then gjkCache (in the warm-start cache's order). */
#include "shared/polyhedral_contacts.h"
#include "shared/soft_afresh.h"
#define BTG_PERSISTENT_STEP btgPairStep
/* The soft step collides two spheres, a box or hull on a plane and a capsule on a box or a
 * plane afresh with speculative points (Box2D's; soft_afresh.h); every other pair here keeps
 * its persistent manifold in both modes. */
#define BTG_SPECULATIVE_COLLIDE btgCollideSoftAfresh
#define BTG_SPECULATIVE_PAIR(kind, shapeA, shapeB) btgSoftCollidesAfresh(kind, shapeA, shapeB)
#define BTG_FRESH_KERNEL 1 /* those pairs are collide_fresh's, a kernel without GJK's registers, */
#define BTG_FRESH_PAIR(kind, shapeA, shapeB) btgSoftFreshKernelPair(kind, shapeA, shapeB) /* but a capsule on a box */
#define BTG_FRESH_COLLIDE btgCollideSoftFresh
#include "shared/persistent_kernels.h"

BTG_PERSISTENT_PROGRAM_KERNEL(BTG_PAIR_KINDS_NARROWPHASE_GJK)
/* the kinds btgSoftCollidesAfresh may name */
BTG_FRESH_PROGRAM_KERNEL(BTG_PAIR_SPHERE_SPHERE, BTG_PAIR_HULL_PLANE, BTG_PAIR_PLANE_BOX, BTG_PAIR_PLANE_CONVEX)

