/* report_contacts.cl — Stage: report_contacts (the app's dispatcher manifolds, Config::
 * fillDispatcherManifolds). Packs each solved contact manifold of the call's last substep into
 * the compact record the host turns into a btPersistentManifold (shared/contact_report.h).
 * Launch: one work-item per contact slot (contactCapacity), after store_contact_cache and before
 * integrate_transforms (the bodies still where the contacts were built).
 * Reads contacts, contactManifolds, manifolds, counters[kContactCount], pos, rot; pairs, props,
 * shapes, children, gjkPairState and subPairs to mark a persistent pair's manifold.
 * Writes reports[0, min(count, capacity)). */
#include "shared/counters.h"
#include "shared/types.h"
#include "shared/contact_report.h"
#include "shared/compound.h"
#include "shared/pair_kinds.h"
#include "shared/mesh.h"

__kernel void report_contacts(__global const BtgContact* restrict contacts,
                              __global const uint* restrict contactManifolds,
                              __global const BtgManifold* restrict manifolds, __global const uint* restrict counters,
                              int contactCapacity, __global const BtgFloat4* restrict pos,
                              __global const BtgFloat4* restrict rot, __global BtgContactReport* reports,
                              __global const BtgPair* restrict pairs, __global const BtgBodyProps* restrict props,
                              __global const BtgShape* restrict shapes, __global const BtgChild* restrict children,
                              __global const BtgPersistentManifold* restrict gjkPairState, int gjkCapacity,
                              uint base, __global const BtgSubPair* restrict subPairs, uint subPairCapacity)
{
    uint i = (uint)get_global_id(0);
    uint n = min(counters[BTG_COUNTER_CONTACTS], (uint)contactCapacity);
    if (i >= n) return;
    BtgContact c = contacts[i];
    const uint slot = contactManifolds[i];
    BtgManifold m = manifolds[slot];
    BtgContactReport r = btgContactReportFrom(&c, m, pos[m.bodyA], rot[m.bodyA], pos[m.bodyB], rot[m.bodyB]);
    /* A persistent pair's state is the one the narrowphase left at its pair's slot (as
     * store_persistent_manifolds finds it): the manifold's own slot, or for a convex–concave
     * pair's group the slot of its sub-pairs' pair. */
    const uint pairSlot = btgManifoldPair(slot, base, subPairs, subPairCapacity);
    if (pairSlot < (uint)gjkCapacity)
        r.persistent = btgHasPersistentState(pairs[pairSlot], gjkPairState[pairSlot], props, shapes, children);
    reports[i] = r;
}
