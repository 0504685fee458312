/* color_constraints.cl — Stage: batching (greedy graph coloring of the contacts).
 * Launch: one work-item per contact slot (contactCapacity) for color_init / color_claim /
 * color_assign / color_finish, one per body for claim_reset / body_color_reset. Each color is
 * filled in a few sub-rounds: every uncolored contact whose dynamic bodies are still free in
 * this color claims them with atomic_min of a hashed priority (a fixed bijection of its index,
 * so neighbouring contacts do not form long chains of losers); those that own all their bodies
 * take the color and mark the bodies used. Integer atomics only: the coloring is a pure
 * function of the contact list. Reads counters[kContactCount], props (flags), contacts.
 * Writes contacts.color, claim and bodyColor (per-body scratch), counters[kColorsUsed],
 * counters[kLeftovers]. */
#include "shared/types.h"
#include "shared/math.h"
#include "shared/contact_rows.h"

#include "shared/coloring.h"
#include "shared/counters.h"
#include "shared/grid_barrier.h"

#define NO_CLAIM 0x7fffffff


static int contact_count(__global const uint* restrict counters, int contactCapacity)
{
    return (int)min(counters[BTG_COUNTER_CONTACTS], (uint)contactCapacity);
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

__kernel void body_color_reset(__global int* bodyColor, int numBodies)
{
    int b = (int)get_global_id(0);
    if (b < numBodies) bodyColor[b] = -1;
}

/* claim and bodyColor go through BTG_SHARED (volatile on GPUs) pointers: color_resident shares them between
 * work-groups across its grid barriers, where a non-coherent cache must not serve a stale
 * copy. Same arithmetic for every caller. */
static int body_free(__global const BtgBodyProps* restrict props, BTG_SHARED __global const int* bodyColor, int body,
                     int color)
{
    return !btgIsSolverDynamic(props[body].flags) || bodyColor[body] != color;
}

/* One contact's claim in a sub-round: an uncolored contact whose dynamic bodies are still free
 * in this color bids for them with its priority. */
static void claim_contact(__global const BtgContact* restrict contacts, int i, __global const BtgBodyProps* restrict props,
                          BTG_SHARED __global int* claim, BTG_SHARED __global const int* bodyColor, int color)
{
    if (contacts[i].color >= 0) return;
    int a = contacts[i].bodyA, b = contacts[i].bodyB;
    if (!body_free(props, bodyColor, a, color) || !body_free(props, bodyColor, b, color)) return;
    int p = btgColorPriority(i);
    if (btgIsSolverDynamic(props[a].flags)) atomic_min(&claim[a], p);
    if (btgIsSolverDynamic(props[b].flags)) atomic_min(&claim[b], p);
}

/* One contact's assignment: it takes the color when it won every dynamic body it bid for. */
static void assign_contact(__global BtgContact* contacts, int i, __global uint* counters,
                           __global const BtgBodyProps* restrict props, BTG_SHARED __global const int* claim,
                           BTG_SHARED __global int* bodyColor, int color)
{
    if (contacts[i].color >= 0) return;
    int a = contacts[i].bodyA, b = contacts[i].bodyB;
    if (!body_free(props, bodyColor, a, color) || !body_free(props, bodyColor, b, color)) return;
    int p = btgColorPriority(i);
    int dynA = btgIsSolverDynamic(props[a].flags), dynB = btgIsSolverDynamic(props[b].flags);
    if ((dynA && claim[a] != p) || (dynB && claim[b] != p)) return;
    contacts[i].color = color;
    /* Only this contact owns these bodies now: plain stores are race-free. */
    if (dynA) bodyColor[a] = color;
    if (dynB) bodyColor[b] = color;
    atomic_max(&counters[BTG_COUNTER_COLORS_USED], (uint)(color + 1));
}

__kernel void color_claim(__global const BtgContact* restrict contacts, __global const uint* restrict counters,
                          int contactCapacity, __global const BtgBodyProps* restrict props, __global int* claim,
                          __global const int* restrict bodyColor, int color)
{
    int i = (int)get_global_id(0);
    if (i < contact_count(counters, contactCapacity)) claim_contact(contacts, i, props, claim, bodyColor, color);
}

__kernel void color_assign(__global BtgContact* contacts, __global uint* counters, int contactCapacity,
                           __global const BtgBodyProps* restrict props, __global const int* restrict claim,
                           __global int* bodyColor, int color)
{
    int i = (int)get_global_id(0);
    if (i < contact_count(counters, contactCapacity)) assign_contact(contacts, i, counters, props, claim, bodyColor, color);
}

/* Contacts left after the rounds share the last color, which the solver runs serially. */
__kernel void color_finish(__global BtgContact* contacts, __global uint* counters, int contactCapacity,
                           int lastColor)
{
    int i = (int)get_global_id(0);
    if (i < contact_count(counters, contactCapacity) && contacts[i].color < 0) {
        contacts[i].color = lastColor;
        atomic_inc(&counters[BTG_COUNTER_LEFTOVERS]);
    }
}

/* color_resident: the whole batching in ONE launch (resident groups on GPUs, one group for
 * small scenes on CPUs): the same
 * init, claim/assign sub-rounds and finish as the per-launch kernels, with a grid barrier
 * (shared/grid_barrier.h) where those have a kernel boundary, so the coloring is identical.
 * Contact i is handled by the same work-item in every round (its color is read and written by
 * no other); claims and body colors are shared, through BTG_SHARED pointers and atomics. */
__kernel void color_resident(__global BtgContact* contacts, __global uint* counters, int contactCapacity,
                             __global const BtgBodyProps* restrict props, BTG_SHARED __global int* claim,
                             BTG_SHARED __global int* bodyColor, int numBodies, int rounds,
                             volatile __global BtgGridBarrier* bar, int spinLimit)
{
    __local int quit;
    const int gid = (int)get_global_id(0), gsize = (int)get_global_size(0);
    const int n = contact_count(counters, contactCapacity);
    for (int i = gid; i < n; i += gsize) contacts[i].color = -1;
    for (int b = gid; b < numBodies; b += gsize) bodyColor[b] = -1;
    int stop = btgGridBarrier(bar, spinLimit, &quit);
    for (int color = 0; color < rounds && !stop; ++color) {
        for (int sub = 0; sub < BTG_COLOR_SUB_ROUNDS && !stop; ++sub) {
            for (int b = gid; b < numBodies; b += gsize) claim[b] = NO_CLAIM;
            stop = btgGridBarrier(bar, spinLimit, &quit);
            if (stop) break;
            for (int i = gid; i < n; i += gsize) claim_contact(contacts, i, props, claim, bodyColor, color);
            stop = btgGridBarrier(bar, spinLimit, &quit);
            if (stop) break;
            for (int i = gid; i < n; i += gsize) assign_contact(contacts, i, counters, props, claim, bodyColor, color);
            stop = btgGridBarrier(bar, spinLimit, &quit);
        }
    }
    if (stop) {
        if (gid == 0) atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_GRID_BARRIER_TIMEOUT);
        return;
    }
    for (int i = gid; i < n; i += gsize)
        if (contacts[i].color < 0) {
            contacts[i].color = rounds;
            atomic_inc(&counters[BTG_COUNTER_LEFTOVERS]);
        }
}
