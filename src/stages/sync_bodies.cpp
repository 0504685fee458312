// sync_bodies.cpp — column sizing, scatter of changed rows, readback.
#include "stages/sync_bodies.h"

#include <algorithm>

namespace btgpu {

void resizeBodies(DeviceWorld& w, int n)
{
    cl::Context& c = w.ctx;
    size_t rows = size_t(n > 0 ? n : 1);
    w.pos.reserve(c, rows, true);
    w.rot.reserve(c, rows, true);
    w.linVel.reserve(c, rows, true);
    w.angVel.reserve(c, rows, true);
    w.props.reserve(c, rows, true);
    w.extForce.reserve(c, rows, true);
    w.extTorque.reserve(c, rows, true);
    w.invInertiaWorld.reserve(c, 3 * rows);
    w.pushLin.reserve(c, rows);
    w.pushAng.reserve(c, rows);
    w.linVel0.reserve(c, rows);
    w.angVel0.reserve(c, rows);
    w.aabbMin.reserve(c, rows);
    w.aabbMax.reserve(c, rows);
    w.sleepTime.reserve(c, rows, true);
    w.islandTime.reserve(c, rows, true);
    w.islandScratch.reserve(c, rows);
    w.wake.reserve(c, rows);
    w.sleepState.reserve(c, rows, true);
    w.counters.reserve(c, kNumCounters, true);
    w.numBodies = n;
}

void syncIn(DeviceWorld& w, const std::vector<BodyRowUpdate>& updates)
{
    if (updates.empty()) return;
    std::vector<int> rows;
    std::vector<BtgFloat4> states;
    std::vector<BtgBodyProps> props;
    rows.reserve(updates.size());
    states.reserve(6 * updates.size());
    props.reserve(updates.size());
    for (const BodyRowUpdate& u : updates) {
        rows.push_back(u.row);
        states.insert(states.end(), {u.pos, u.rot, u.linVel, u.angVel, u.force, u.torque});
        props.push_back(u.props);
    }
    w.stagingRows.upload(w.ctx, rows);
    w.stagingStates.upload(w.ctx, states);
    w.stagingProps.upload(w.ctx, props);
    int n = int(updates.size());
    cl::Launch(w.ctx, w.ctx.program("sync_bodies").kernel("scatter_bodies"), &w.profiler)
        .arg(n).arg(w.stagingRows).arg(w.stagingStates).arg(w.stagingProps).arg(w.pos).arg(w.rot).arg(w.linVel).arg(w.angVel)
        .arg(w.extForce).arg(w.extTorque).arg(w.props)
        .run(size_t(n));
}

void resetRows(DeviceWorld& w, const std::vector<int>& rows)
{
    if (rows.empty()) return;
    w.stagingRows.upload(w.ctx, rows);
    cl::Launch(w.ctx, w.ctx.program("sync_bodies").kernel("reset_rows"), &w.profiler)
        .arg(int(rows.size())).arg(w.stagingRows).arg(w.sleepTime).arg(w.islandTime).arg(w.sleepState)
        .run(rows.size());
}

void syncOut(DeviceWorld& w, BodyReadback& out)
{
    size_t n = size_t(w.numBodies);
    out.pos.resize(w.ctx, n);
    out.rot.resize(w.ctx, n);
    out.linVel.resize(w.ctx, n);
    out.angVel.resize(w.ctx, n);
    out.sleepState.resize(w.ctx, n);
    out.counters.resize(w.ctx, kNumCounters);
    // Non-blocking reads queued together, one wait: a single round trip per call.
    w.pos.readAsync(w.ctx, out.pos.data(), n);
    w.rot.readAsync(w.ctx, out.rot.data(), n);
    w.linVel.readAsync(w.ctx, out.linVel.data(), n);
    w.angVel.readAsync(w.ctx, out.angVel.data(), n);
    w.sleepState.readAsync(w.ctx, out.sleepState.data(), n);
    w.counters.readAsync(w.ctx, out.counters.data(), kNumCounters);
    // The contact reports travel in the same round trip: as many as the last call had plus an
    // eighth are read ahead; only a count past that costs a second read, of the rest.
    out.contactsValid = w.contactReportsWritten;
    size_t ahead = 0;
    if (w.contactReportsWritten) {
        const size_t last = size_t(std::max(w.lastContactCount, 0));
        ahead = std::min(w.contactReports.capacity(), last + last / 8 + 64);
        out.contacts.resize(w.ctx, w.contactReports.capacity());
        w.contactReports.readAsync(w.ctx, out.contacts.data(), ahead);
    }
    w.ctx.finish();
    if (w.contactReportsWritten) {
        const size_t count = std::min<size_t>(out.counters[kContactCount], w.contactReports.capacity());
        if (count > ahead) w.contactReports.download(w.ctx, out.contacts.data() + ahead, count - ahead, ahead);
        out.numContacts = count;
        w.contactReportsWritten = false;
    }
}

}  // namespace btgpu
