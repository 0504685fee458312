// midphase.h — Stage: midphase. Splits every convex–mesh pair of the broadphase into (convex,
// triangle) sub-pairs: the convex's box in the mesh's frame walked through Bullet's quantized
// BVH (kernels/shared/mesh.h). Count, scan, write: the sub-pairs come out grouped by pair in
// pair order, each pair's triangles in walk order, with no sort and no atomics.
// Reads pairs, pairOrder, pairKindRanges, pos, rot, props, shapes, meshes, meshNodes, meshParts.
// Writes subPairOffsets, subPairs, counters[kSubPairCount]; BTG_STATUS_SUB_PAIR_OVERFLOW when
// they exceed subPairCapacity (runCall grows the buffer and redoes the step). Also makes
// `manifolds` hold pairCapacity + subPairCapacity slots for the triangles' manifolds.
#pragma once
#include "world/device_world.h"

namespace btgpu {
void midphase(DeviceWorld& w);
}
