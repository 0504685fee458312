// filter_pairs.h — Stage: pairs whose objects ignore each other's collision check
// (setIgnoreCollisionCheck, disableCollisionsBetweenLinkedBodies) get no contacts: their
// manifold ranges are emptied after the narrowphase. Reads w.ignoredPairs, pairs, counters.
// Writes pairManifolds.
#pragma once
#include "world/device_world.h"

namespace btgpu {
void filterPairs(DeviceWorld& w);
}
