// narrowphase_gjk.h — Stage: the pair kinds with a persistent manifold: the GJK kinds (a convex
// shape known by its support function against any convex or a plane: each pair's one new point,
// GJK/EPA, the capsule closed form or the plane's support point) and two boxes (stock's box
// detector's points, program narrowphase_sat), into the pair's persistent manifold as Bullet's
// algorithms and btPersistentManifold; after the solve, the manifolds kept for the next substep.
// (Convex–concave pairs: narrowphase.cpp's narrowphaseMesh.) Reads pairs, pairOrder, pairKindRanges, pos, rot, props, shapes, hullVertices, counters,
// contactCache, gjkCache. Writes manifolds, pairManifolds and gjkPairState of those pairs;
// storePersistentManifolds reads contacts (friction anchors) and writes gjkCache (contact order).
#pragma once
#include "world/device_world.h"
#include "world/pair_kinds.h"

#include <vector>

namespace btgpu {
// The buffers a narrowphase with persistent manifolds reads and writes, sized, and the GJK
// cache's stale entries cleared (once after it was left unstored); where no pair of `kinds`
// keeps a manifold (keepsPersistentManifolds), one entry of no kind each instead.
void preparePersistent(DeviceWorld& w, const PairKinds& kinds);
// The slots of gjkPairState the collide kernels write: all of them, or none where no pair
// keeps a manifold.
int persistentStateCapacity(const DeviceWorld& w, const PairKinds& kinds);
// The kernels of `program` (one of those two) for the kinds in `kinds`.
void narrowphasePersistent(DeviceWorld& w, const PairKinds& kinds, const char* program);
// After storeContactCache: contact i's persistent manifold to gjkCache[i], with the friction
// anchors the next refresh keeps (solverFlags: BtgStepParams.solverFlags).
void storePersistentManifolds(DeviceWorld& w, const PairKinds& kinds, unsigned solverFlags);
// The convex–concave manifolds kept against these body rows' meshes or heightfields are
// forgotten (the next substep starts those pairs afresh): the app edited the shapes.
void forgetConcaveManifolds(DeviceWorld& w, const std::vector<int>& rows);
}  // namespace btgpu
