// narrowphase_gjk.h — Stage: the pair kinds with a persistent manifold: the GJK kinds (a convex
// shape known by its support function against any convex or a plane: each pair's one new point,
// GJK/EPA, the capsule closed form or the plane's support point) and two boxes (stock's box
// detector's points, program narrowphase_sat), into the pair's persistent manifold as Bullet's
// algorithms and btPersistentManifold; after the solve, the manifolds kept for the next substep.
// Reads pairs, pairOrder, pairKindRanges, pos, rot, props, shapes, hullVertices, counters,
// contactCache, gjkCache. Writes manifolds, pairManifolds and gjkPairState of those pairs;
// storePersistentManifolds reads contacts (friction anchors) and writes gjkCache (contact order).
#pragma once
#include "world/device_world.h"
#include "world/pair_kinds.h"

namespace btgpu {
// Whether any kind in `kinds` keeps a persistent manifold (programs narrowphase_sat, narrowphase_gjk).
bool anyPersistent(const PairKinds& kinds);
// The kernels of `program` (one of those two) for the kinds in `kinds`.
void narrowphasePersistent(DeviceWorld& w, const PairKinds& kinds, const char* program);
// After storeContactCache: contact i's persistent manifold to gjkCache[i], with the friction
// anchors the next refresh keeps (solverFlags: BtgStepParams.solverFlags).
void storePersistentManifolds(DeviceWorld& w, const PairKinds& kinds, unsigned solverFlags);
}  // namespace btgpu
