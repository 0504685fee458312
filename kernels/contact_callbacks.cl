/* contact_callbacks.cl — Stage: contact_callbacks (gContactAddedCallback on the GPU path). A
 * substep stops after its contacts are found (the manifolds) and before the contact list; the
 * host reads the manifolds of pairs with a CF_CUSTOM_MATERIAL_CALLBACK body (all of them with a
 * custom combiner), runs the app's callbacks on each point, writes back what they changed, and
 * the substep goes on.
 * With an overlap filter callback the host first empties the ranges of the pairs Bullet's pair
 * cache does not hold (clear_pair_ranges, one work-item per refused pair).
 * Launch: gather_callback_manifolds one work-item per pair slot (pairCapacity), each gathered
 * manifold with the points its persistent pair added this substep (gjkPairState.addedMask by
 * id, a convex–concave pair's addedPoints by place with BTG_ADDED_BY_POSITION; -2: not
 * persistent, all its points are this substep's);
 * scatter_callback_manifolds one per changed manifold; apply_contact_materials one per contact
 * slot (contactCapacity), right after prepare_contacts.
 * Reads pairManifolds, manifolds, props (BTG_BODY_CUSTOM_MATERIAL), counters[kPairCount,
 * kContactCount]; the changed manifolds and materials the host uploaded; for the materials
 * prepare_contacts' inputs (props, invInertiaWorld, linVel0, angVel0, linVel, angVel).
 * Writes gathered slots and copies (count in gatherCount[0], even past capacity); manifolds at
 * the changed slots; the contacts whose manifold has a material (their rows prepared again). */
#include "shared/counters.h"
#include "shared/types.h"
#include "shared/math.h"
#include "shared/contact_rows.h"
#include "shared/contact_material.h"
#include "shared/compound.h"
#include "shared/pair_kinds.h"

__kernel void gather_callback_manifolds(__global const BtgManifoldRange* restrict pairManifolds,
                                        __global const BtgManifold* restrict manifolds,
                                        __global const BtgBodyProps* restrict props,
                                        __global const uint* restrict counters, int pairCapacity,
                                        __global uint* gatherCount, __global uint* slots,
                                        __global BtgManifold* copies, int capacity, int all,
                                        __global const BtgPair* restrict pairs, __global const BtgShape* restrict shapes,
                                        __global const BtgChild* restrict children,
                                        __global const BtgPersistentManifold* restrict gjkPairState, int gjkCapacity,
                                        __global int* added)
{
    uint i = (uint)get_global_id(0);
    uint n = min(counters[BTG_COUNTER_PAIRS], (uint)pairCapacity);
    if (i >= n) return;
    BtgManifoldRange r = pairManifolds[i];
    /* A persistent manifold (box and GJK pairs) keeps its points: which ones this substep added
     * (the points the app's added callback is called for), from the pair's state the
     * narrowphase left, as a mask of their identities. */
    int addedId = -2;
    uint byPosition = 0u; /* a convex–concave pair's: its points' feature ids are triangle keys */
    if ((int)i < gjkCapacity && btgHasPersistentState(pairs[i], gjkPairState[i], props, shapes, children)) {
        addedId = (int)gjkPairState[i].addedMask;
        if (btgIsConcaveKind(gjkPairState[i].kind)) byPosition = gjkPairState[i].addedPoints;
    }
    int emitted = 0;
    for (int j = r.start; j < r.start + r.count; ++j) {
        BtgManifold m = manifolds[j];
        if (addedId != -2 && btgIsConcaveKind(gjkPairState[i].kind))
            addedId = (int)(BTG_ADDED_BY_POSITION | ((byPosition >> emitted) & 0xfu));
        emitted += m.numPoints;
        if (m.numPoints <= 0) continue;
        if (!all && !((props[m.bodyA].flags | props[m.bodyB].flags) & BTG_BODY_CUSTOM_MATERIAL)) continue;
        uint k = atomic_inc(gatherCount);
        if (k >= (uint)capacity) continue;
        slots[k] = (uint)j;
        copies[k] = m;
        added[k] = addedId;
    }
}

__kernel void scatter_callback_manifolds(__global const uint* restrict slots,
                                         __global const BtgManifold* restrict changed, int n,
                                         __global BtgManifold* manifolds)
{
    int i = (int)get_global_id(0);
    if (i >= n) return;
    manifolds[slots[i]] = changed[i];
}

__kernel void apply_contact_materials(__global BtgContact* contacts, __global const uint* restrict contactManifolds,
                                      __global const uint* restrict counters, int contactCapacity,
                                      __global const BtgContactMaterial* restrict materials, int numMaterials,
                                      __global const BtgBodyProps* restrict props,
                                      __global const BtgFloat4* restrict invInertiaWorld,
                                      __global const BtgFloat4* restrict linVel0, __global const BtgFloat4* restrict angVel0,
                                      __global const BtgFloat4* restrict linVel, __global const BtgFloat4* restrict angVel,
                                      BtgStepParams params)
{
    uint i = (uint)get_global_id(0);
    const uint n = min(counters[BTG_COUNTER_CONTACTS], (uint)contactCapacity);
    if (i >= n) return;
    const int found = btgFindMaterial(materials, numMaterials, contactManifolds[i]);
    if (found < 0) return;
    BtgContact c = contacts[i];
    const BtgContactBodies t = btgLoadContactBodies(c, props, invInertiaWorld, linVel0, angVel0, linVel, angVel);
    const BtgBodyProps pa = t.pa, pb = t.pb;
    const BtgSolverBody a = t.a, b = t.b;
    const BtgBodyVel a0 = t.a0, b0 = t.b0, a1 = t.a1, b1 = t.b1;
    btgApplyContactMaterial(&c, materials[found], btgPairMaterial(pa, pb), a, b, a0, b0, a1, b1, btgContactSolvable(pa.flags, pb.flags), params);
    contacts[i] = c;
}

/* The pairs an app's overlap filter callback refused (Bullet's pair cache holds no such pair):
 * their manifold ranges emptied, as filter_pairs does, so no contact is made of them. */
__kernel void clear_pair_ranges(__global const uint* restrict refused, int n, __global BtgManifoldRange* pairManifolds)
{
    int i = (int)get_global_id(0);
    if (i >= n) return;
    pairManifolds[refused[i]].count = 0;
}
