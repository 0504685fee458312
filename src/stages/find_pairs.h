// find_pairs.h — Stage: broadphase. The small bodies by uniform grid (radix sort of cell
// hashes, cell ranges by scan) or by sort-and-sweep (stages/sort_sweep.h), as the plan chose;
// a pass of the `largeBodies` against every body, and the `planeBodies` against every body by
// a plane/AABB test. Both small-body passes find the same pairs, so the result does not depend
// on the choice.
// Reads aabbMin, aabbMax, props (flags, group, mask, shape), largeBodies, planeBodies, pos, rot, shapes.
// Writes pairs (a < b, sorted by (a, b), no duplicates), pairManifolds (none yet), pairOrder
// and pairKindRanges (the
// pairs grouped by kind: sorted by (kind, a, b), each kind's range found on the device; see
// groupPairsByKind) and counters[kPairCount]. When more
// pairs are found than pairCapacity, the count still says how many, BTG_STATUS_PAIR_OVERFLOW
// is set in counters[kStatus], and the caller grows the buffer and redoes the step.
// A pair is kept when: neither body is EXCLUDED or NO_RESPONSE; at least one is DYNAMIC and
// not SLEEPING; (groupA & maskB) && (groupB & maskA); the AABBs overlap.
#pragma once
#include "world/device_world.h"
#include "world/plan.h"

namespace btgpu {
// cellSize (m) is used by the grid only.
// The two stages of it: the small bodies' pass (the plan's uniform_grid or sort_sweep), which
// starts the pair count, then find_pairs (large and plane passes, sort, gather into pairs,
// grouping by the plan's kinds).
void smallBodyPairs(DeviceWorld& w, Broadphase broadphase, float cellSize);
// group false: the pairs are left in (a, b) order only (expand_compounds groups them after it
// has replaced the compound pairs by their leaves).
void finishPairs(DeviceWorld& w, const PairKinds& kinds, bool group = true);
// Both, in order.
void findPairs(DeviceWorld& w, const PairKinds& kinds, Broadphase broadphase, float cellSize);
// The last step of finishPairs, for `pairs` as they stand (tests upload their own): the pairs'
// slots ordered by (kind, a, b) into pairOrder (stable radix pass on the kind: within a kind
// the (a, b) order) and kind k's range into pairKindRanges[BTG_KIND_RANGE_*(k)], all on the
// device (a pair's kind is its two sides' shapes', a compound's leaf included). With a single kind in `kinds`, no sort: its range is every pair slot in place, the
// others empty, and pairKindsIndirect is false.
void groupPairsByKind(DeviceWorld& w, const PairKinds& kinds);
}
