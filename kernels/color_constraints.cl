/* color_constraints.cl — Stage: batching (greedy graph coloring of the contacts).
 * Launch: one work-item per contact slot (contactCapacity) for color_init / color_claim /
 * color_assign / color_finish, one per body for claim_reset. Each round, every uncolored contact
 * claims its dynamic bodies with atomic_min of its index; those that own all of them take the
 * round's color. Integer atomics only, so the coloring is a pure function of the contact list.
 * Reads counters[kContactCount], props (flags), contacts (bodyA, bodyB). Writes contacts.color,
 * claim (per-body scratch). */
#include "shared/types.h"
#include "shared/math.h"
#include "shared/contact_rows.h"

#define COUNTER_CONTACTS 1 /* mirrors btgpu::Counter */
#define NO_CLAIM 0x7fffffff

static int contact_count(__global const uint* restrict counters, int contactCapacity)
{
    return (int)min(counters[COUNTER_CONTACTS], (uint)contactCapacity);
}

__kernel void color_init(__global BtgContact* contacts, __global const uint* restrict counters, int contactCapacity)
{
    int i = (int)get_global_id(0);
    if (i < contact_count(counters, contactCapacity)) contacts[i].color = -1;
}

__kernel void claim_reset(__global int* claim, int numBodies)
{
    int b = (int)get_global_id(0);
    if (b < numBodies) claim[b] = NO_CLAIM;
}

__kernel void color_claim(__global const BtgContact* restrict contacts, __global const uint* restrict counters,
                          int contactCapacity, __global const BtgBodyProps* restrict props, __global int* claim)
{
    int i = (int)get_global_id(0);
    if (i >= contact_count(counters, contactCapacity) || contacts[i].color >= 0) return;
    int a = contacts[i].bodyA, b = contacts[i].bodyB;
    if (btgIsSolverDynamic(props[a].flags)) atomic_min(&claim[a], i);
    if (btgIsSolverDynamic(props[b].flags)) atomic_min(&claim[b], i);
}

__kernel void color_assign(__global BtgContact* contacts, __global const uint* restrict counters, int contactCapacity,
                           __global const BtgBodyProps* restrict props, __global const int* restrict claim, int color)
{
    int i = (int)get_global_id(0);
    if (i >= contact_count(counters, contactCapacity) || contacts[i].color >= 0) return;
    int a = contacts[i].bodyA, b = contacts[i].bodyB;
    int ownA = !btgIsSolverDynamic(props[a].flags) || claim[a] == i;
    int ownB = !btgIsSolverDynamic(props[b].flags) || claim[b] == i;
    if (ownA && ownB) contacts[i].color = color;
}

/* Contacts left after the rounds share the last color, which the solver runs serially. */
__kernel void color_finish(__global BtgContact* contacts, __global const uint* restrict counters, int contactCapacity,
                           int lastColor)
{
    int i = (int)get_global_id(0);
    if (i < contact_count(counters, contactCapacity) && contacts[i].color < 0) contacts[i].color = lastColor;
}
