// broadphase_leaves.h — Stage: stock's broadphase pairs, found on the device. Every substep
// each row's Dbvt leaf follows its stock AABB (updateLeaves); in a call's last substep the pairs
// whose leaves overlap are listed and compared with the last call's list (leafPairs); after the
// call only the change travels (readLeafChanges). Reads pos, rot, linVel, angVel, props, shapes;
// writes DeviceWorld::leaves (src/world/leaf_buffers.h).
#pragma once
#include "world/device_world.h"

#include <vector>

namespace btgpu {

// What a call changed in the overlapping leaf pairs (rows, a < b, in (a, b) order), and the
// counts stock's lazy pair cleanup reads (btDbvtBroadphase::collide).
struct LeafChanges {
    std::vector<BtgPair> added;
    std::vector<BtgPair> removed;
    std::vector<BtgPair> transient;  // met by stock's pass (added to its cache) though their leaves part by its end
    unsigned pairs = 0;     // pairs whose leaves overlap now
    unsigned newPairs = 0;  // overlaps the moved leaves met in stock's order (m_newpairs less its 1)
    unsigned moved = 0;     // leaf moves in the call (any: m_needcleanup)
    bool redone = false;    // the list overflowed, grew and was made again
};

// The pair lists' capacity (grown on overflow by readLeafChanges; tests start it small).
void reserveLeafPairs(DeviceWorld& w, size_t capacity);
// Before a call's substeps: the moved flags and counts of the last call cleared.
void startLeafCall(DeviceWorld& w);
// Each substep right after predict_motion: threshold is the contact breaking threshold (m).
void updateLeaves(DeviceWorld& w, float threshold, float dt);
// The call's last substep: the overlapping pairs, sorted, and their difference with the last list.
// cellSize (m): the sweep's (y, z) cells, about twice the largest small leaf (bigger leaves, two
// cells or more, are paired against every row).
void leafPairs(DeviceWorld& w, float cellSize);
// After the call: the difference (the list grown and made again if it overflowed); this call's
// list becomes the one the next call is compared with.
LeafChanges readLeafChanges(DeviceWorld& w);

}  // namespace btgpu
