// report_contacts.cpp — host launcher of the contact report: one work-item per contact slot
// into the reports (sized as the contact list: contactReports, or the soft step's dead rows),
// flagged for syncOut to read back.
#include "stages/report_contacts.h"

#include "cl/program.h"
#include "stages/sync_bodies.h"

#include <algorithm>

namespace btgpu {

void reportContacts(DeviceWorld& w, bool overSoftRows)
{
    cl::Context& ctx = w.ctx;
    unmapReports(w);  // the last call's reports, mapped for the fill on a CPU device: written anew now
    const int contactCapacity = int(std::min({w.contactCapacity, w.contacts.capacity(), w.contactManifolds.capacity()}));
    const size_t n = size_t(std::max(contactCapacity, 1));
    w.reports = w.solverScratch.afterSolve(ctx, w.contactReports, n, overSoftRows);
    w.subPairs.reserve(ctx, 1);  // read only for a manifold past the pair slots: a convex–concave group
    cl::Launch(ctx, ctx.program("report_contacts").kernel("report_contacts"), &w.profiler)
        .arg(w.contacts).arg(w.contactManifolds).arg(w.manifolds).arg(w.counters).arg(contactCapacity).arg(w.pos)
        .arg(w.rot).arg(w.reports).arg(w.pairs).arg(w.props).arg(w.shapes).arg(w.children).arg(w.gjkPairState)
        .arg(int(std::min({w.gjkPairState.capacity(), w.pairCapacity, w.pairs.capacity()})))
        .arg(cl_uint(w.pairCapacity)).arg(w.subPairs).arg(cl_uint(w.subPairCapacity))
        .run(n);
    w.contactReportsWritten = true;
}

}  // namespace btgpu
