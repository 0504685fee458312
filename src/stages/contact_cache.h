// contact_cache.h — Stage: this step's contact list and its warm start.
// Compacts the manifolds that have points into `contacts` (in pair order, so the list is a
// pure function of the sorted pairs) and sets counters[kContactCount]; sets
// BTG_STATUS_CONTACT_OVERFLOW when they exceed contactCapacity. For each new point, finds the
// previous step's contact of the same body pair (prevContacts, sorted by (bodyA, bodyB),
// counters[kPrevContactCount]) and the old point nearest in A's frame within
// params.contactThreshold, and starts from its impulses times params.warmstartFactor.
// Reads manifolds, pairs, counters, pos, rot, props, prevContacts. Writes contacts
// (bodyA, bodyB, numPoints, normal, rA/rB/localA geometry, impulses), counters.
// After the step the pipeline swaps contacts and prevContacts.
#pragma once
#include "world/device_world.h"

namespace btgpu {
void buildContacts(DeviceWorld& w, const BtgStepParams& params);
}
