// contact_cache.h — Stage: this step's contact list and its warm start.
// Compacts the manifolds that have points into `contacts` (in pair order, so the list is a
// pure function of the sorted pairs) and sets counters[kContactCount]; sets
// BTG_STATUS_CONTACT_OVERFLOW when they exceed contactCapacity. For each new point, finds the
// previous step's contact of the same body pair (prevContacts, sorted by (bodyA, bodyB),
// counters[kPrevContactCount]) and the old point nearest in A's frame within
// params.contactThreshold, and starts from its impulses times params.warmstartFactor.
// rA = point on A - posA, rB = point on B - posB (Bullet's rel_pos1/rel_pos2); localA.w = distance.
// Reads manifolds, counters, pos, rot, prevContacts. Writes contacts (bodyA, bodyB, numPoints,
// normal, rA/rB/localA geometry, impulses; color -1), counters, solverScratch.blockSums.
// After the step the pipeline swaps contacts and prevContacts.
#pragma once
#include "world/device_world.h"

namespace btgpu {
void buildContacts(DeviceWorld& w, const BtgStepParams& params);
}
