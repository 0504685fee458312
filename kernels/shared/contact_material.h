/* contact_material.h — what the host's contact callbacks (compat/contact_callbacks.cpp: Bullet's
 * gContactAddedCallback on bodies with CF_CUSTOM_MATERIAL_CALLBACK) hand back to one contact
 * manifold before the solve: its combined friction and each point's combined restitution, as
 * the callback left them, and the preparation of the contact's rows again with those. Shared by
 * contact_callbacks.cl and its CPU reference. */
#ifndef BTG_CONTACT_MATERIAL_H
#define BTG_CONTACT_MATERIAL_H
#include "prelude.h"
#include "types.h"
#include "math.h"
#include "contact_rows.h"

typedef struct {
    BtgFloat4 restitution; /* per point: combined restitution coefficient (btManifoldPoint's) */
    float friction;        /* the manifold's combined friction coefficient (its points share it) */
    uint slot;             /* the manifold slot (contactManifolds' value); sorted ascending */
    uint pad0;
    uint pad1;
} BtgContactMaterial;

#ifndef __OPENCL_C_VERSION__
static_assert(sizeof(BtgContactMaterial) == 32, "BtgContactMaterial layout");
#endif

/* The material of manifold slot `slot` among materials[0, n) (sorted by slot), or -1. */
static inline int btgFindMaterial(BTG_CONST_GLOBAL BtgContactMaterial* materials, int n, uint slot)
{
    int lo = 0, hi = n;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (materials[mid].slot < slot) lo = mid + 1;
        else hi = mid;
    }
    return lo < n && materials[lo].slot == slot ? lo : -1;
}

/* Contact c, already prepared (prepare_contacts) with the bodies' own combination, prepared
 * again with the callback's friction and per-point restitution: btgPrepareContact is a function
 * of the contact's geometry, so preparing twice changes only what friction and restitution
 * enter — the friction, and through restitution each point's normal target. A point whose
 * restitution differs from point 0's takes its target from a preparation with its own. */
static inline void btgApplyContactMaterial(BtgContact* c, BtgContactMaterial m, BtgPairMaterial pair, BtgSolverBody a,
                                           BtgSolverBody b, BtgBodyVel a0, BtgBodyVel b0, BtgBodyVel a1,
                                           BtgBodyVel b1, int solvable, BtgStepParams p)
{
    const BtgContact base = *c;
    /* The pair's own material (rolling and spinning friction, contact stiffness) with the
     * callback's friction and restitution. */
    pair.friction = m.friction;
    pair.restitution = btgLane(m.restitution, 0);
    btgPrepareContact(c, a, b, a0, b0, a1, b1, pair, solvable, p);
    for (int k = 1; k < c->numPoints; ++k) {
        const float r = btgLane(m.restitution, k);
        int seen = 0;
        for (int j = 0; j < k; ++j) seen |= btgLane(m.restitution, j) == r;
        if (seen) continue;
        BtgContact t = base;
        BtgPairMaterial own = pair;
        own.restitution = r;
        btgPrepareContact(&t, a, b, a0, b0, a1, b1, own, solvable, p);
        for (int j = k; j < c->numPoints; ++j)
            if (btgLane(m.restitution, j) == r) btgSetLane(&c->normalTarget, j, btgLane(t.normalTarget, j));
    }
}

#endif
