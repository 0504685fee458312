// contact_cache.h — Stage: this step's contact list, its warm start, and the cache.
// buildContacts compacts each pair's range of manifolds with points (pairManifolds) into
// `contacts` (in pair order, so the list is a pure function of the sorted pairs), the manifold
// slot of each into contactManifolds, and sets counters[kContactCount]; sets
// BTG_STATUS_CONTACT_OVERFLOW when they exceed contactCapacity. For each manifold, finds the
// cached manifold it continues (contactCache, sorted by (bodyA, bodyB): the entries of its body
// pair with the same sub-shape keys, counters[kPrevContactCount]) and for each new point the
// old point nearest in A's frame within the pair's breakingThreshold (carried by its
// manifold), and starts from its impulses times params.warmstartFactor.
// rA = point on A - posA (w: signed distance, until prepare), rB = point on B - posB (Bullet's
// rel_pos1/rel_pos2). Reads pairManifolds, manifolds, counters, pos, rot, contactCache. Writes
// contacts (bodyA, bodyB, numPoints, normal, rA/rB, impulses; color -1), contactManifolds,
// counters, solverScratch.blockSums.
// storeContactCache runs after the solve and before integrate_transforms (the keys are R_A^T rA
// with A's rotation as the contacts were built): writes contactCache (BtgCachedContact: keys,
// normal impulses, the manifold's sub-shape keys and feature ids, read through
// contactManifolds) and counters[kPrevContactCount], unless the substep overflowed.
// The cache's entries of pairs whose bodies both sleep or stand (not collided, as on stock) are
// carried into the new cache, merged in by pair key, so a woken pile warm-starts from them:
// noteCarried (before the wake, with the flags the pairs were found with) ranks them;
// storeContactCache writes the new cache into contactCacheNext and swaps the two (the soft step:
// into its rows' storage, dead after its solve, and copies it back over the old); countCache,
// after the persistent manifolds' store when there is one, sets the count.
#pragma once
#include "world/device_world.h"

namespace btgpu {
void buildContacts(DeviceWorld& w, const BtgStepParams& params);
// carry: deactivation is on (bodies may sleep); else nothing is carried.
void noteCarried(DeviceWorld& w, bool carry);
// count: set the cache's count now (no persistent manifolds' store follows).
// overSoftRows: the soft step solved this substep (SolverScratch::rowsAs).
void storeContactCache(DeviceWorld& w, bool count = true, bool overSoftRows = false);
void countCache(DeviceWorld& w);
}
