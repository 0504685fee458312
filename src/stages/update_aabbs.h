// update_aabbs.h — Stage: world AABBs of every body row.
// Reads pos, rot, props (shape, flags), shapes. Writes aabbMin, aabbMax for rows
// [0, numBodies), grown by `threshold` m on each side (the contact threshold, as Bullet grows
// its AABBs by the contact breaking threshold). Planes get a degenerate AABB (never gridded).
#pragma once
#include "world/device_world.h"

namespace btgpu {
void updateAabbs(DeviceWorld& w, float threshold);
}
