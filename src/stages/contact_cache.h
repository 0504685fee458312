// contact_cache.h — Stage: this step's contact list, its warm start, and the cache.
// buildContacts compacts the manifolds that have points into `contacts` (in pair order, so the
// list is a pure function of the sorted pairs) and sets counters[kContactCount]; sets
// BTG_STATUS_CONTACT_OVERFLOW when they exceed contactCapacity. For each new point, finds the
// cached contact of the same body pair (contactCache, sorted by (bodyA, bodyB),
// counters[kPrevContactCount]) and the old point nearest in A's frame within
// the pair's breakingThreshold (carried by its manifold), and starts from its impulses times
// params.warmstartFactor.
// rA = point on A - posA (w: signed distance, until prepare), rB = point on B - posB (Bullet's
// rel_pos1/rel_pos2). Reads manifolds, counters, pos, rot, contactCache. Writes contacts
// (bodyA, bodyB, numPoints, normal, rA/rB, impulses; color -1), counters, solverScratch.blockSums.
// storeContactCache runs after the solve and before integrate_transforms (the keys are R_A^T rA
// with A's rotation as the contacts were built): writes contactCache (BtgCachedContact: keys,
// normal impulses) and counters[kPrevContactCount], unless the substep overflowed.
#pragma once
#include "world/device_world.h"

namespace btgpu {
void buildContacts(DeviceWorld& w, const BtgStepParams& params);
void storeContactCache(DeviceWorld& w);
}
