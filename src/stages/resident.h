// resident.h — launch shape of the resident kernels (kernels/shared/grid_barrier.h): the
// batching and the solve run all their rounds in one launch over work-groups that wait for
// each other, on GPUs, where a launch costs a few microseconds and those stages have hundreds
// of rounds a step. Never more groups than compute units, so all are resident at once; the
// batching takes only enough for one round's work (fewer groups, cheaper barriers), the solve
// one per compute unit (see solve_constraints.cpp).
#pragma once
#include "world/device_world.h"

#include <algorithm>

namespace btgpu {

inline bool useResident(const DeviceWorld& w)
{
    using R = DeviceWorld::Resident;
    return w.resident == R::On || (w.resident == R::Auto && w.ctx.device().isGpu);
}

// Work-groups of `group` items for `items` of work per round (each item a few per work-item).
inline size_t residentGroups(const DeviceWorld& w, size_t items, size_t group)
{
    size_t perGroup = 4 * std::max<size_t>(group, 1);
    size_t groups = (items + perGroup - 1) / perGroup;
    return std::clamp<size_t>(groups, 1, std::max<cl_uint>(w.ctx.device().computeUnits, 1));
}

// The barrier word, zeroed once when allocated: a normal exit leaves it ready for the next launch.
inline cl::DeviceArray<uint>& gridBarrier(DeviceWorld& w)
{
    cl::DeviceArray<uint>& bar = w.solverScratch.gridBarrier;
    if (bar.capacity() == 0) bar.zero(w.ctx, 4);
    return bar;
}

// Polls before a waiter gives up (a poll is an L2 round trip; a round's work is at most a few
// hundred microseconds, so this is far past any real wait).
constexpr int kGridBarrierSpins = 1 << 20;

}  // namespace btgpu
