// sort_sweep.h — Stage: broadphase, the sort-and-sweep pass over the small bodies (the rows
// btgGridded takes), used by find_pairs in place of the uniform grid when the plan says so.
// Reads aabbMin, aabbMax, props, shapes. Appends every allowed AABB-overlapping pair of small
// rows to broadphase.rawPairs with the grid pass's protocol (counters[kPairCount] counts all,
// only slots below `capacity` are written); find_pairs sorts them by (a, b) afterwards, so the
// final list equals the grid's. Writes the sort-and-sweep scratch (broadphase.sap*).
#pragma once
#include "world/device_world.h"

namespace btgpu {
void sortSweepPairs(DeviceWorld& w, cl_uint capacity);
}
