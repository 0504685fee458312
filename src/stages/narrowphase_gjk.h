// narrowphase_gjk.h — Stage: the GJK pair kinds (a convex shape known by its support function
// against any convex or a plane): each pair's one new point (GJK/EPA, the capsule closed form,
// or the plane's support point) into its persistent manifold, as Bullet's convex algorithms and
// btPersistentManifold; after the solve, the manifolds kept for the next substep.
// Reads pairs, pairOrder, pairKindRanges, pos, rot, props, shapes, hullVertices, counters,
// contactCache, gjkCache. Writes manifolds, pairManifolds and gjkPairState of those pairs;
// storePersistentManifolds writes gjkCache (contact order).
#pragma once
#include "world/device_world.h"
#include "world/pair_kinds.h"

namespace btgpu {
// The kernels of program "narrowphase_gjk" for the kinds in `kinds`.
void narrowphaseGjk(DeviceWorld& w, const PairKinds& kinds);
// After storeContactCache: contact i's persistent manifold to gjkCache[i].
void storePersistentManifolds(DeviceWorld& w);
}  // namespace btgpu
