/* report_contacts.cl — Stage: report_contacts (the app's dispatcher manifolds, Config::
 * fillDispatcherManifolds). Packs each solved contact manifold of the call's last substep into
 * the compact record the host turns into a btPersistentManifold (shared/contact_report.h).
 * Launch: one work-item per contact slot (contactCapacity), after store_contact_cache and before
 * integrate_transforms (the bodies still where the contacts were built).
 * Reads contacts, contactManifolds, manifolds, counters[kContactCount], pos, rot.
 * Writes reports[0, min(count, capacity)). */
#include "shared/counters.h"
#include "shared/types.h"
#include "shared/contact_report.h"

__kernel void report_contacts(__global const BtgContact* restrict contacts,
                              __global const uint* restrict contactManifolds,
                              __global const BtgManifold* restrict manifolds, __global const uint* restrict counters,
                              int contactCapacity, __global const BtgFloat4* restrict pos,
                              __global const BtgFloat4* restrict rot, __global BtgContactReport* reports)
{
    uint i = (uint)get_global_id(0);
    uint n = min(counters[BTG_COUNTER_CONTACTS], (uint)contactCapacity);
    if (i >= n) return;
    BtgContact c = contacts[i];
    BtgManifold m = manifolds[contactManifolds[i]];
    reports[i] = btgContactReportFrom(&c, m, pos[m.bodyA], rot[m.bodyA], pos[m.bodyB], rot[m.bodyB]);
}
