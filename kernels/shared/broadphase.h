/* broadphase.h — the pair rules and geometric tests of find_pairs, shared by
 * kernels/find_pairs.cl, kernels/sort_sweep.cl and the CPU references so all keep exactly the
 * same pairs: the rows of the small-body pass, the filter, AABB overlap (touching counts, as
 * Bullet's TestAabbAgainstAabb2), the plane test, the grid cell and hash of an AABB centre,
 * and (device only) the append of a found pair. */
#ifndef BTG_BROADPHASE_H
#define BTG_BROADPHASE_H
#include "math.h"
#include "counters.h"
#include "types.h"

#ifdef __OPENCL_C_VERSION__
static inline float btgFloor(float x) { return floor(x); }
#else
static inline float btgFloor(float x) { return std::floor(x); }
#endif

/* Cells further than this from the origin are clamped: keeps the float-to-int conversion
 * defined; bodies out there share cells (still correct, only slower). */
#define BTG_GRID_LIMIT 1.0e9f

/* Rows paired by the small-body pass (uniform grid or sort-and-sweep): not large, not a
 * plane (both have their own passes) and able to pair at all. The flags are tested first:
 * an excluded row may have no shape (shape -1). */
static inline int btgGridded(BtgBodyProps p, BTG_CONST_GLOBAL BtgShape* shapes)
{
    uint skip = BTG_BODY_LARGE | BTG_BODY_EXCLUDED | BTG_BODY_NO_SHAPE;
    return !(p.flags & skip) && shapes[p.shape].type != BTG_SHAPE_PLANE;
}

/* Bullet's dispatcher collides a pair the filter masks allow when either body is active
 * (needsCollision), whether or not it responds (a CF_NO_CONTACT_RESPONSE trigger gets its
 * manifold, unsolved). Active: an awake dynamic or kinematic body (stock's kinematic bodies
 * sleep as dynamic ones do; static ones are added asleep). Default masks keep kinematic and
 * static bodies apart; custom ones may ask for those pairs. */
static inline int btgPairAllowed(BtgBodyProps a, BtgBodyProps b)
{
    /* A btEmptyShape is concave to Bullet's dispatcher: against it a convex shape's algorithm
       walks no triangles, two concave shapes get the empty algorithm. */
    if ((a.flags | b.flags) & (BTG_BODY_EXCLUDED | BTG_BODY_NO_SHAPE)) return 0;
    uint moving = BTG_BODY_DYNAMIC | BTG_BODY_KINEMATIC;
    int aActive = (a.flags & moving) && !(a.flags & BTG_BODY_SLEEPING);
    int bActive = (b.flags & moving) && !(b.flags & BTG_BODY_SLEEPING);
    /* A kinematic body reaching a sleeping one must be seen: it wakes it, as in Bullet. */
    int aWakes = (a.flags & BTG_BODY_KINEMATIC) && (b.flags & BTG_BODY_DYNAMIC) && (b.flags & BTG_BODY_SLEEPING);
    int bWakes = (b.flags & BTG_BODY_KINEMATIC) && (a.flags & BTG_BODY_DYNAMIC) && (a.flags & BTG_BODY_SLEEPING);
    if (!aActive && !bActive && !aWakes && !bWakes) return 0;
    return (a.group & b.mask) != 0 && (b.group & a.mask) != 0;
}

static inline int btgAabbOverlap(BtgFloat4 aMin, BtgFloat4 aMax, BtgFloat4 bMin, BtgFloat4 bMax)
{
    return !(aMin.x > bMax.x || aMax.x < bMin.x || aMin.y > bMax.y || aMax.y < bMin.y ||
             aMin.z > bMax.z || aMax.z < bMin.z);
}

/* The plane (shape param: xyz unit normal n, w constant c, body frame) in world space:
 * xyz R n, w c + (R n).pos, so that world points p on it satisfy n'.p = w'. */
static inline BtgFloat4 btgPlaneWorld(BtgFloat4 pos, BtgFloat4 rot, BtgFloat4 param)
{
    BtgFloat4 n = btgQuatRotate(rot, btgXyz(param));
    return btgMake4(n.x, n.y, n.z, param.w + btgDot3(n, pos));
}

/* The AABB reaches the plane's solid side when its corner furthest against the normal does. */
static inline int btgAabbReachesPlane(BtgFloat4 aMin, BtgFloat4 aMax, BtgFloat4 plane)
{
    BtgFloat4 c = btgMake4(plane.x > 0.0f ? aMin.x : aMax.x, plane.y > 0.0f ? aMin.y : aMax.y,
                           plane.z > 0.0f ? aMin.z : aMax.z, 0.0f);
    return btgDot3(plane, c) - plane.w <= 0.0f;
}

static inline int btgGridCoord(float x, float invCellSize)
{
    return (int)btgFloor(btgClamp(x * invCellSize, -BTG_GRID_LIMIT, BTG_GRID_LIMIT));
}

/* Cell of an AABB's centre: with cells no smaller than any gridded AABB, overlapping AABBs
 * lie in the same or adjacent cells. */
static inline BtgInt4 btgGridCell(BtgFloat4 aMin, BtgFloat4 aMax, float invCellSize)
{
    BtgFloat4 c = (aMin + aMax) * 0.5f;
    BtgInt4 cell;
    cell.x = btgGridCoord(c.x, invCellSize);
    cell.y = btgGridCoord(c.y, invCellSize);
    cell.z = btgGridCoord(c.z, invCellSize);
    cell.w = 0;
    return cell;
}

/* Spatial hash (Teschner et al. primes) into a power-of-two table; unsigned wrap-around. */
static inline uint btgGridHash(int x, int y, int z, uint tableMask)
{
    return (((uint)x * 73856093u) ^ ((uint)y * 19349663u) ^ ((uint)z * 83492791u)) & tableMask;
}

#ifdef __OPENCL_C_VERSION__
/* The appending protocol of every pair pass (device only): every pair found is counted, only
 * those that fit are stored (the caller grows the buffer and redoes the step). */
static inline void btgAppendPair(__global BtgPair* restrict raw, volatile __global uint* counters,
                                 uint capacity, int a, int b)
{
    uint slot = atomic_inc(&counters[BTG_COUNTER_PAIRS]);
    if (slot < capacity) {
        BtgPair p;
        p.a = a < b ? a : b;
        p.b = a < b ? b : a;
        p.childA = BTG_WHOLE_BODY;
        p.childB = BTG_WHOLE_BODY;
        raw[slot] = p;
    }
}
#endif

#endif
