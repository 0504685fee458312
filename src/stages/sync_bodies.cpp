// sync_bodies.cpp — column sizing, scatter of changed rows, readback.
#include "stages/sync_bodies.h"

#include <algorithm>

namespace btgpu {

void resizeBodies(DeviceWorld& w, int n)
{
    cl::Context& c = w.ctx;
    size_t rows = size_t(n > 0 ? n : 1);
    // New rows belong to no sleeping island and mark none.
    const size_t hadLabels = std::min(w.islandLabel.capacity(), size_t(std::max(w.numBodies, 0)));
    w.islandLabel.reserve(c, rows, true);
    w.islandLabelScratch.reserve(c, rows);
    w.islandWake.reserve(c, rows, true);
    if (rows > hadLabels) {
        w.islandLabel.fill(c, 0xffffffffu, hadLabels, rows - hadLabels);
        w.islandWake.fill(c, 0u, hadLabels, rows - hadLabels);
    }
    w.pos.reserve(c, rows, true);
    w.rot.reserve(c, rows, true);
    w.linVel.reserve(c, rows, true);
    w.angVel.reserve(c, rows, true);
    w.props.reserve(c, rows, true);
    w.extForce.reserve(c, rows, true);
    w.extTorque.reserve(c, rows, true);
    w.invInertiaWorld.reserve(c, 3 * rows);
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

void syncIn(DeviceWorld& w, const BodyRowUploads& updates)
{
    if (updates.empty()) return;
    w.stagingRows.upload(w.ctx, updates.rows.data(), updates.rows.size());
    w.stagingStates.upload(w.ctx, updates.states.data(), updates.states.size());
    w.stagingProps.upload(w.ctx, updates.props.data(), updates.props.size());
    int n = int(updates.size());
    cl::Launch(w.ctx, w.ctx.program("sync_bodies").kernel("scatter_bodies"), &w.profiler)
        .arg(n).arg(w.stagingRows).arg(w.stagingStates).arg(w.stagingProps).arg(w.pos).arg(w.rot).arg(w.linVel).arg(w.angVel)
        .arg(w.extForce).arg(w.extTorque).arg(w.props)
        .run(size_t(n));
}

void writeColumns(DeviceWorld& w, const BodyColumns& c)
{
    const size_t n = c.size();
    if (n == 0) return;
    w.pos.upload(w.ctx, c.pos.data(), n);
    w.rot.upload(w.ctx, c.rot.data(), n);
    w.linVel.upload(w.ctx, c.linVel.data(), n);
    w.angVel.upload(w.ctx, c.angVel.data(), n);
    w.extForce.upload(w.ctx, c.force.data(), n);
    w.extTorque.upload(w.ctx, c.torque.data(), n);
    w.props.upload(w.ctx, c.props.data(), n);
}

void resetRows(DeviceWorld& w, const std::vector<int>& rows, bool woken)
{
    if (rows.empty()) return;
    w.stagingRows.upload(w.ctx, rows);
    cl::Launch(w.ctx, w.ctx.program("sync_bodies").kernel("reset_rows"), &w.profiler)
        .arg(int(rows.size())).arg(w.stagingRows).arg(w.sleepTime).arg(w.islandTime).arg(w.sleepState)
        .arg(w.islandLabel).arg(w.islandWake).arg(w.numBodies).arg(woken ? 1 : 0)
        .run(rows.size());
}

void setSleepTimes(DeviceWorld& w, const std::vector<int>& rows, const std::vector<float>& times)
{
    if (rows.empty()) return;
    w.stagingRows.upload(w.ctx, rows);
    w.stagingTimes.upload(w.ctx, times);
    cl::Launch(w.ctx, w.ctx.program("sync_bodies").kernel("set_sleep_times"), &w.profiler)
        .arg(int(rows.size())).arg(w.stagingRows).arg(w.stagingTimes).arg(w.sleepTime)
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
    out.sleepTime.resize(w.ctx, n);
    out.counters.resize(w.ctx, kNumCounters);
    // Non-blocking reads queued together, one wait: a single round trip per call.
    w.pos.readAsync(w.ctx, out.pos.data(), n);
    w.rot.readAsync(w.ctx, out.rot.data(), n);
    w.linVel.readAsync(w.ctx, out.linVel.data(), n);
    w.angVel.readAsync(w.ctx, out.angVel.data(), n);
    w.sleepState.readAsync(w.ctx, out.sleepState.data(), n);
    w.sleepTime.readAsync(w.ctx, out.sleepTime.data(), n);
    cl_event counted = nullptr;
    w.counters.readAsync(w.ctx, out.counters.data(), kNumCounters, 0, &counted);
    // The contact reports are queued behind those: as many as the last call had plus an eighth
    // ahead, the rest (a count past that) once the counters are in. The call waits for the
    // counters only (the queue is in order: the bodies' rows are in too); the reports travel
    // while the host writes the bodies back, and awaitReports waits for them before the
    // manifold fill (on a GPU their copy is the step's largest: 10.8 MB at 8,000 cubes).
    out.contactsValid = w.contactReportsWritten;
    unmapReports(w);  // (report_contacts undid it already when it ran)
    // A CPU device's memory is the host's: the fill reads the reports where the device wrote
    // them, mapped once the count is in, instead of a copy (PoCL: 1 ms a step at cubes 8,000).
    const bool mapped = !w.ctx.device().isGpu;
    size_t ahead = 0;
    if (w.contactReportsWritten && !mapped) {
        // (None ahead when there was no last call, whose count stands at a huge placeholder
        // until then: the first step read the whole capacity, 736 MB at 1,000,000 cubes.)
        const size_t last = size_t(std::max(w.lastContactCount, 0));
        ahead = last >= w.reports.capacity() ? 0 : std::min(w.reports.capacity(), last + last / 8 + 64);
        // The pinned copy holds what is read, grown a quarter past it (it was sized to the
        // whole contact capacity: 736 MB pinned at 1,000,000 falling cubes with none touching).
        if (out.contacts.size() < ahead) out.contacts.resize(w.ctx, std::min(w.reports.capacity(), ahead + ahead / 4));
        w.reports.readAsync(w.ctx, out.contacts.data(), ahead);
    }
    BTGPU_CL_CHECK(clFlush(w.ctx.queue()));  // the reads under way before the host blocks
    const cl_int waited = clWaitForEvents(1, &counted);
    clReleaseEvent(counted);
    BTGPU_CL_CHECK(waited);
    if (w.contactReportsWritten && mapped) {
        const size_t count = std::min<size_t>(out.counters[kContactCount], w.reports.capacity());
        cl_int err = CL_SUCCESS;
        void* p = clEnqueueMapBuffer(w.ctx.queue(), w.reports.mem(), CL_TRUE, CL_MAP_READ, 0,
                                     std::max<size_t>(count, 1) * sizeof(BtgContactReport), 0, nullptr, nullptr, &err);
        BTGPU_CL_CHECK(err);
        w.reportsMapped = p;
        out.reports = static_cast<const BtgContactReport*>(p);
        out.numContacts = count;
        out.reportsPending = false;
        w.contactReportsWritten = false;
    } else if (w.contactReportsWritten) {
        const size_t count = std::min<size_t>(out.counters[kContactCount], w.reports.capacity());
        if (count > ahead && out.contacts.size() < count) {
            // More than the copy holds: what was read ahead is waited for and kept.
            w.ctx.finish();
            const std::vector<BtgContactReport> kept(out.contacts.data(), out.contacts.data() + ahead);
            out.contacts.resize(w.ctx, std::min(w.reports.capacity(), count + count / 4));
            std::copy(kept.begin(), kept.end(), out.contacts.data());
        }
        if (count > ahead) w.reports.readAsync(w.ctx, out.contacts.data() + ahead, count - ahead, ahead);
        out.reports = out.contacts.data();
        out.numContacts = count;
        out.reportsPending = true;
        w.contactReportsWritten = false;
    }
}

void unmapReports(DeviceWorld& w)
{
    if (!w.reportsMapped) return;
    void* p = w.reportsMapped;
    w.reportsMapped = nullptr;
    BTGPU_CL_CHECK(clEnqueueUnmapMemObject(w.ctx.queue(), w.reports.mem(), p, 0, nullptr, nullptr));
}

void awaitReports(DeviceWorld& w, BodyReadback& out)
{
    if (!out.reportsPending) return;
    w.ctx.finish();
    out.reportsPending = false;
}

}  // namespace btgpu
