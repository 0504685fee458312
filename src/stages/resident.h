// resident.h — launch shape of the resident kernels (kernels/shared/grid_barrier.h): the
// batching and the solve run all their rounds in one launch over work-groups that wait for
// each other, on GPUs, where a launch costs a few microseconds and those stages have hundreds
// of rounds a step. Never more groups than compute units, so all are resident at once; the
// batching takes only enough for one round's work (fewer groups, cheaper barriers), the solve
// one per compute unit (see solve_constraints.cpp).
#pragma once
#include "shared/grid_barrier.h"
#include "world/device_world.h"

#include <algorithm>
#include <cstdlib>

namespace btgpu {

inline bool useResident(const DeviceWorld& w)
{
    using R = DeviceWorld::Resident;
    // BTGPU_RESIDENT=0 / 1: per-round launches / one launch on every device (an experiment
    // knob, as below)
    static const int forced = [] {
        const char* e = std::getenv("BTGPU_RESIDENT");
        return e && e[0] ? (e[0] == '0' ? 0 : 1) : -1;
    }();
    if (forced >= 0) return forced == 1 && w.resident != R::Off;
    return w.resident == R::On || (w.resident == R::Auto && w.ctx.device().isGpu);
}

// Whether a stage may take one launch over resident groups where it prefers to (not after the
// world went over to per-round launches, nor with BTGPU_RESIDENT=0).
inline bool residentAllowed(const DeviceWorld& w)
{
    const char* e = std::getenv("BTGPU_RESIDENT");
    return w.resident != DeviceWorld::Resident::Off && !(e && e[0] == '0');
}

// Work-groups of `group` items for `items` of work per round (each item a few per work-item).
inline size_t residentGroups(const DeviceWorld& w, size_t items, size_t group)
{
    size_t perGroup = 4 * std::max<size_t>(group, 1);
    size_t groups = (items + perGroup - 1) / perGroup;
    return std::clamp<size_t>(groups, 1, std::max<cl_uint>(w.ctx.device().computeUnits, 1));
}

// Work-groups of the solvers' one-launch kernels: one per compute unit; or, experiment knobs for
// measuring, BTGPU_RESIDENT_GROUPS_PER_UNIT=k (k per unit: all must be resident at once; a
// device that does not keep them so times out at the first grid barrier and the world goes over
// to per-round launches, CallEvent::Kind::ResidentOff) or BTGPU_RESIDENT_GROUPS=n (at most one
// per unit). H200, soft step at cubes 32,768: 2 or 4 a unit 6.10 / 5.70 ms against 4.91 with
// one, 66 or 33 groups 5.01 / 8.11.
inline size_t residentSolveGroups(const DeviceWorld& w)
{
    const size_t units = std::max<cl_uint>(w.ctx.device().computeUnits, 1);
    if (const char* e = std::getenv("BTGPU_RESIDENT_GROUPS")) return std::clamp<size_t>(size_t(std::max(std::atoi(e), 1)), 1, units);
    size_t perUnit = 1;
    if (const char* e = std::getenv("BTGPU_RESIDENT_GROUPS_PER_UNIT")) perUnit = size_t(std::clamp(std::atoi(e), 1, 32));
    return perUnit * units;
}

// The batched PGS's one-launch solve: one group per compute unit, but no more than its contacts
// (as of the last readback) give a group kPgsContactsPerGroup of, nor fewer than kPgsMinGroups.
// Every group arrives at each of the step's hundreds of grid barriers, one atomic at one word
// each: in a small scene the arrivals cost more than the parallelism they buy. H100, 2026-12-06
// (tests/bench/small_scenes_on_gpu.sh, median frame ms over 200, two runs, groups 2 / 4 / 8 /
// 16 / 32 / 66 / 132): cubes 125 1.35 / 1.35-1.47 / 1.36-1.42 / 1.35 / 1.36-1.40 / 1.35-1.37 /
// 1.44-1.55; cubes 1,000 2.76-2.80 / 2.21-2.25 / 2.19-2.41 / 2.18-2.32 / 2.16-2.20 /
// 2.17-2.19 / 2.17-2.22; cubes 8,000 from 32 groups within 4%, 32,768 best at 132. The groups
// split the same colour ranges: bitwise the same results whatever the count (state hashes).
// BTGPU_RESIDENT_GROUPS still sets the count outright.
constexpr size_t kPgsContactsPerGroup = 64;
constexpr size_t kPgsMinGroups = 16;
inline size_t residentPgsGroups(const DeviceWorld& w)
{
    const size_t all = residentSolveGroups(w);
    if (std::getenv("BTGPU_RESIDENT_GROUPS")) return all;
    const size_t contacts = size_t(std::max(w.lastContactCount, 0));
    const size_t wanted = std::max(kPgsMinGroups, (contacts + kPgsContactsPerGroup - 1) / kPgsContactsPerGroup);
    return std::min(all, wanted);
}

// Work-items of a group of the solvers' one-launch kernels where the groups are resident (one per
// compute unit): `preferred` (the stage's choice), else 256 for the one group of a small scene
// on a CPU; or BTGPU_RESIDENT_GROUP_SIZE (an experiment knob, as above); within the kernel's
// limit. Each contact is a chain of dependent loads, so a sweep wants about one work-item per
// contact of a colour, and every idle warp still waits at each of the step's hundreds of
// barriers (measurements in solve_constraints.cpp and solve_soft.cpp).
inline size_t residentSolveGroupSize(size_t kernelLimit, bool resident, size_t preferred)
{
    size_t size = resident ? preferred : 256;
    if (const char* e = std::getenv("BTGPU_RESIDENT_GROUP_SIZE")) size = size_t(std::clamp(std::atoi(e), 32, 1024));
    return std::max<size_t>(std::min(size, kernelLimit), 1);
}

// The barrier word, zeroed once when allocated: a normal exit leaves it ready for the next launch.
inline cl::DeviceArray<uint>& gridBarrier(DeviceWorld& w)
{
    cl::DeviceArray<uint>& bar = w.solverScratch.gridBarrier;
    if (bar.capacity() == 0) bar.zero(w.ctx, BTG_GRID_BARRIER_WORDS);
    return bar;
}

// Polls before a waiter gives up: on a GPU a poll is an L2 round trip (about half a
// microsecond; a round's work is at most a few hundred microseconds, so this is far past any real
// wait); on a CPU a poll hits its own cache in nanoseconds, and a group may wait for another's
// thread to be woken or scheduled: about as long there.
constexpr int kGridBarrierSpins = 1 << 20;
inline int gridBarrierSpins(const DeviceWorld& w)
{
    return w.ctx.device().isGpu ? kGridBarrierSpins : kGridBarrierSpins << 10;
}

}  // namespace btgpu
