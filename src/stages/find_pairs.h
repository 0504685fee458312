// find_pairs.h — Stage: broadphase. Uniform grid (radix sort of cell hashes, cell ranges by
// scan) for bodies of similar size, a pass of the `largeBodies` against every body, and the
// `planeBodies` against every body by a plane/AABB test.
// Reads aabbMin, aabbMax, props (flags, group, mask), largeBodies, planeBodies, pos, rot, shapes.
// Writes pairs (a < b, sorted by (a, b), no duplicates) and counters[kPairCount]. When more
// pairs are found than pairCapacity, the count still says how many, BTG_STATUS_PAIR_OVERFLOW
// is set in counters[kStatus], and the caller grows the buffer and redoes the step.
// A pair is kept when: neither body is EXCLUDED or NO_RESPONSE; at least one is DYNAMIC and
// not SLEEPING; (groupA & maskB) && (groupB & maskA); the AABBs overlap.
#pragma once
#include "world/device_world.h"

namespace btgpu {
void findPairs(DeviceWorld& w, float cellSize);
}
