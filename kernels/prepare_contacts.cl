/* prepare_contacts.cl — Stage: prepare (solver rows of each contact, setupContactConstraint,
 * and the contacts' edges of the constraint graph).
 * Launch: one work-item per contact slot (contactCapacity); early-out past the contact count.
 * Reads counters[kContactCount], props, invInertiaWorld, rot (anisotropic friction), linVel0,
 * angVel0 (restitution), linVel, angVel (after this substep's forces: each point's friction
 * direction), contacts.
 * softStep: the plan's solver is the soft step (btgPrepareSoftContact where it reads no more).
 * Writes contacts (friction, tangent plane and per-point friction directions, row masses,
 * normalCfm, normalTarget, pushTarget, pushImpulse zeroed; impulses of non-solvable contacts
 * zeroed), rolling[0, contacts) (BTG_SOLVER_ROLLING_FRICTION only), frictionDirs[0, contacts)
 * (BTG_SOLVER_ANISOTROPIC_FRICTION only), anchors[0, contacts) (BTG_SOLVER_FRICTION_ANCHORS only:
 * the friction rows' positional targets, from pos), edges[0, contacts) (edge i: contact i's
 * bodies), counters[kEdgeCount] (= the contacts; kinds that follow append to it). */
#include "shared/counters.h"
#include "shared/types.h"
#include "shared/math.h"
#include "shared/contact_rows.h"
#include "shared/material_rows.h"


__kernel void prepare_contacts(__global BtgContact* contacts, __global uint* counters,
                               int contactCapacity, __global const BtgBodyProps* restrict props,
                               __global const BtgFloat4* restrict invInertiaWorld,
                               __global const BtgFloat4* restrict rot,
                               __global const BtgFloat4* restrict linVel0, __global const BtgFloat4* restrict angVel0,
                               __global const BtgFloat4* restrict linVel, __global const BtgFloat4* restrict angVel,
                               __global BtgEdge* edges, __global BtgRollingContact* rolling,
                               __global BtgFrictionDirs* frictionDirs, __global const BtgFloat4* restrict pos,
                               __global BtgFrictionAnchor* anchors, BtgStepParams params, int softStep)
{
    uint i = (uint)get_global_id(0);
    const uint n = min(counters[BTG_COUNTER_CONTACTS], (uint)contactCapacity);
    if (i == 0) counters[BTG_COUNTER_EDGES] = n;
    if (i >= n) return;
    BtgContact c = contacts[i];
    edges[i] = btgContactEdge(c);
    const BtgContactBodies t = btgLoadContactBodies(c, props, invInertiaWorld, linVel0, angVel0, linVel, angVel);
    const BtgBodyProps pa = t.pa, pb = t.pb;
    const BtgSolverBody a = t.a, b = t.b;
    const BtgBodyVel a0 = t.a0, b0 = t.b0, a1 = t.a1, b1 = t.b1;
    const BtgPairMaterial mat = btgPairMaterial(pa, pb);
    const int solvable = btgContactSolvable(pa.flags, pb.flags);
    /* the soft step (softStep: the plan's solver) makes its own rows: where it reads nothing else
     * of this stage's (no rolling rows, Bullet's directions or anchors), only what it reads */
    if (softStep && !(params.solverFlags & (BTG_SOLVER_ROLLING_FRICTION | BTG_SOLVER_ANISOTROPIC_FRICTION |
                                            BTG_SOLVER_FRICTION_ANCHORS))) {
        btgPrepareSoftContact(&c, mat, solvable);
        contacts[i] = c;
        return;
    }
    btgPrepareContact(&c, a, b, a0, b0, a1, b1, mat, solvable, params);
    const int anchored = (params.solverFlags & BTG_SOLVER_FRICTION_ANCHORS) != 0u;
    if (params.solverFlags & BTG_SOLVER_ANISOTROPIC_FRICTION) {
        BtgFrictionDirs dirs;
        btgPrepareAnisotropicFriction(&c, &dirs, a, b, a1, b1, rot[c.bodyA], rot[c.bodyB], pa, pb, solvable, params);
        frictionDirs[i] = dirs;
        if (anchored)
            anchors[i] = btgPrepareFrictionAnchor(&c, &dirs, pos[c.bodyA], pos[c.bodyB],
                                                  btgAnchoredPair(pa.flags, pb.flags), params);
    } else if (anchored) {
        anchors[i] = btgPrepareFrictionAnchor(&c, 0, pos[c.bodyA], pos[c.bodyB], btgAnchoredPair(pa.flags, pb.flags),
                                              params);
    }
    contacts[i] = c;
    if (params.solverFlags & BTG_SOLVER_ROLLING_FRICTION)
        rolling[i] = btgPrepareRolling(&c, a, b, mat, solvable, rot[c.bodyA], rot[c.bodyB], pa, pb);
}
