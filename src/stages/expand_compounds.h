// expand_compounds.h — Stage: expand_compounds. Turns every pair of the broadphase with a
// compound side into the pairs of the compound's leaves stock's btCompoundCollisionAlgorithm
// processes (shared/compound.h), in place in `pairs`, which stays sorted by (a, b). Runs after
// find_pairs' (a, b) sort and groups the result by kind (find_pairs' groupPairsByKind).
// Reads pairs, pos, rot, props, shapes, children. Writes compoundOffsets, compoundPairs, pairs,
// pairManifolds, counters[kPairCount]; BTG_STATUS_PAIR_OVERFLOW past pairCapacity (runCall grows
// the pair buffers and redoes the step).
#pragma once
#include "world/device_world.h"
#include "world/pair_kinds.h"

namespace btgpu {
void expandCompounds(DeviceWorld& w, const PairKinds& kinds);
}
