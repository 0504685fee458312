/* update_aabbs.cl — world AABBs of every body row (btgBodyAabb in shared/aabb.h).
 * Stage: update_aabbs. Launch: one work-item per body row, numBodies of them.
 * Reads: pos, rot, props (shape, flags), shapes. Writes: aabbMin, aabbMax (grown by threshold). */
#include "shared/aabb.h"

__kernel void update_aabbs(__global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,
                           __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                           __global BtgFloat4* restrict aabbMin, __global BtgFloat4* restrict aabbMax,
                           int numBodies, float threshold)
{
    int i = (int)get_global_id(0);
    if (i >= numBodies) return;
    BtgBodyProps p = props[i];
    /* An excluded (possibly empty) row's shape index may be invalid: do not read it. */
    BtgAabb a = (p.flags & BTG_BODY_EXCLUDED) ? btgEmptyAabb()
                                              : btgBodyAabb(pos[i], rot[i], shapes[p.shape], p.flags, threshold);
    aabbMin[i] = a.lo;
    aabbMax[i] = a.hi;
}
