// ignored_pairs.h — objects that ignore each other's collision check (btCollisionObject::
// setIgnoreCollisionCheck; addConstraint's disableCollisionsBetweenLinkedBodies sets it between
// the joint's bodies): the pairs of rows Bullet's dispatcher never collides, kept on the device
// for filter_pairs and re-read every step (the app may change them between steps).
#pragma once
#include "row_map.h"
#include "world/device_world.h"

#include <vector>

namespace btgpu {

class IgnoredPairs {
public:
    // Reads every row's exceptions; uploads the pairs when they changed. True when the set went
    // from empty to non-empty or back (the plan gains or loses filter_pairs).
    bool update(const RowMap& rows, DeviceWorld& w);
    bool any() const { return !m_uploaded.empty(); }
    void reset() { m_uploaded.clear(); m_valid = false; }

private:
    std::vector<BtgPair> m_uploaded;
    bool m_valid = false;  // m_uploaded is what the device holds
};

}  // namespace btgpu
