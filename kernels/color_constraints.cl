/* color_constraints.cl — Stage: batching (greedy coloring of the constraint graph: contacts
 * and any other constraint kind's edges together, as Box2D v3's b2GraphColor).
 * Launch: one work-item per edge slot (edgeCapacity) for color_init / color_claim /
 * color_assign / color_finish, one per body for claim_reset / body_color_reset. Each color is
 * filled in a few sub-rounds: every uncolored edge whose dynamic bodies are still free in
 * this color claims them with atomic_min of a hashed priority (a fixed bijection of its index,
 * so neighbouring edges do not form long chains of losers); those that own all their bodies
 * take the color and mark the bodies used. Integer atomics only: the coloring is a pure
 * function of the edge list. Ordered joints (the bullet mode, where stock's solve order of
 * joints that share a body matters; `ordered` from the host): joint j takes colour
 * jointLevels[j] (the host's: one above every joint before it in stock's order that shares a
 * body with it), before any contact bids in that colour (color_joints, or the same pass at the
 * colour's start), and bids for nothing; the contacts fill the colours around them. The solve
 * runs every joint colour before the next, so joints that share a body run in stock's order.
 * Reads counters[kEdgeCount, kContactCount], props (flags), edges, jointLevels (ordered only).
 * Writes edgeColor, claim and bodyColor (per-body scratch), counters[kColorsUsed],
 * counters[kLeftovers]. */
#include "shared/types.h"
#include "shared/solver_rows.h"

#include "shared/coloring.h"
#include "shared/counters.h"
#include "shared/grid_barrier.h"

#define NO_CLAIM 0xffffffffu /* above every priority (coloring.h) */


static int edge_count(__global const uint* restrict counters, int edgeCapacity)
{
    return (int)min(counters[BTG_COUNTER_EDGES], (uint)edgeCapacity);
}

/* The colouring's view of the joints: the buffers and counts every batching kernel takes
 * (jointLevels a one-element placeholder unless ordered). */
#define ORDER_ARGS __global const int* restrict jointLevels, int numJoints, int ordered
#define ORDER_PASS jointLevels, numJoints, ordered

/* Edge i's fixed colour where it is an ordered joint, else -1 (a contact, or joints unordered).
 * Edges below the contact count are contacts, the joints' follow (as prepare_joints appends). */
static int joint_level(__global const uint* restrict counters, int edgeCapacity, int i, ORDER_ARGS)
{
    if (!ordered) return -1;
    const int nc = (int)min(counters[BTG_COUNTER_CONTACTS], (uint)(edgeCapacity - numJoints));
    return i >= nc && i < nc + numJoints ? jointLevels[i - nc] : -1;
}

__kernel void color_init(__global int* edgeColor, __global const uint* restrict counters, int edgeCapacity)
{
    int i = (int)get_global_id(0);
    if (i < edge_count(counters, edgeCapacity)) edgeColor[i] = -1;
}

__kernel void claim_reset(__global uint* claim, int numBodies)
{
    int b = (int)get_global_id(0);
    if (b < numBodies) claim[b] = NO_CLAIM;
}

/* A body no edge colours (not solver-dynamic: static, kinematic, asleep, excluded) holds
 * BODY_FIXED in bodyColor for the whole batching, a dynamic one -1 until an edge takes it: the
 * claims and assignments then read one compact word a body, not its props (a 160-byte row
 * whose flags were a scattered read per side of every edge in every sub-round). */
#define BODY_FIXED (-2)
static int reset_color(__global const BtgBodyProps* restrict props, int b)
{
    return btgIsSolverDynamic(props[b].flags) ? -1 : BODY_FIXED;
}
__kernel void body_color_reset(__global int* bodyColor, __global const BtgBodyProps* restrict props, int numBodies)
{
    int b = (int)get_global_id(0);
    if (b < numBodies) bodyColor[b] = reset_color(props, b);
}

/* claim and bodyColor go through BTG_SHARED (volatile on GPUs) pointers: color_resident shares them between
 * work-groups across its grid barriers, where a non-coherent cache must not serve a stale
 * copy. Same arithmetic for every caller. */
static int body_free(BTG_SHARED __global const int* bodyColor, int body, int color)
{
    return bodyColor[body] != color; /* BODY_FIXED is no colour */
}
static int body_dynamic(BTG_SHARED __global const int* bodyColor, int body)
{
    return bodyColor[body] != BODY_FIXED;
}

/* One edge's claim in a sub-round: an uncolored edge whose dynamic bodies are still free in
 * this color bids for them with its priority. */
static int claim_edge(__global const BtgEdge* restrict edges, __global const int* edgeColor, int i,
                      BTG_SHARED __global uint* claim,
                      BTG_SHARED __global const int* bodyColor, int color, int level)
{
    if (edgeColor[i] >= 0) return 0;
    if (level >= 0) return 1; /* an ordered joint: its colour is its level (mark_joint), no bid */
    int a = edges[i].bodyA, b = edges[i].bodyB;
    if (!body_free(bodyColor, a, color) || !body_free(bodyColor, b, color)) return 1;
    const uint p = btgColorPriority(i);
    if (body_dynamic(bodyColor, a)) atomic_min(&claim[a], p);
    if (body_dynamic(bodyColor, b)) atomic_min(&claim[b], p);
    return 1; /* still uncolored */
}

/* One edge's assignment: it takes the color when it won every dynamic body it bid for. */
static void assign_edge(__global const BtgEdge* restrict edges, __global int* edgeColor, int i, __global uint* counters,
                        BTG_SHARED __global const uint* claim,
                        BTG_SHARED __global int* bodyColor, int color, int level)
{
    if (edgeColor[i] >= 0 || level >= 0) return;
    int a = edges[i].bodyA, b = edges[i].bodyB;
    if (!body_free(bodyColor, a, color) || !body_free(bodyColor, b, color)) return;
    const uint p = btgColorPriority(i);
    int dynA = body_dynamic(bodyColor, a), dynB = body_dynamic(bodyColor, b);
    if ((dynA && claim[a] != p) || (dynB && claim[b] != p)) return;
    edgeColor[i] = color;
    /* Only this edge owns these bodies now: plain stores are race-free. */
    if (dynA) bodyColor[a] = color;
    if (dynB) bodyColor[b] = color;
    /* looked at first: the colour's first edge raises it, the rest find it raised (an atomic for
     * every edge kept the counters' line moving between a CPU device's cores, and every
     * work-item's read of the edge count there waited for it) */
    if (((volatile __global uint*)counters)[BTG_COUNTER_COLORS_USED] < (uint)(color + 1))
        atomic_max(&counters[BTG_COUNTER_COLORS_USED], (uint)(color + 1));
}

/* An ordered joint of level `color` takes the colour and its dynamic bodies, before any
 * contact's bid in it: joints of one level share no dynamic body (the host's levels), and no
 * contact has the colour yet. */
static void mark_joint(__global const BtgEdge* restrict edges, __global int* edgeColor, int i, __global uint* counters,
                       BTG_SHARED __global int* bodyColor, int color, int level)
{
    if (level != color) return;
    edgeColor[i] = color;
    const int a = edges[i].bodyA, b = edges[i].bodyB;
    if (body_dynamic(bodyColor, a)) bodyColor[a] = color;
    if (body_dynamic(bodyColor, b)) bodyColor[b] = color;
    atomic_max(&counters[BTG_COUNTER_COLORS_USED], (uint)(color + 1));
}

__kernel void color_joints(__global const BtgEdge* restrict edges, __global int* edgeColor, __global uint* counters,
                           int edgeCapacity, __global int* bodyColor, int color, ORDER_ARGS)
{
    const int j = (int)get_global_id(0);
    if (j >= numJoints) return;
    const int nc = (int)min(counters[BTG_COUNTER_CONTACTS], (uint)(edgeCapacity - numJoints));
    if (nc + j < edge_count(counters, edgeCapacity)) mark_joint(edges, edgeColor, nc + j, counters, bodyColor, color, jointLevels[j]);
}

__kernel void color_claim(__global const BtgEdge* restrict edges, __global const int* restrict edgeColor,
                          __global const uint* restrict counters, int edgeCapacity, __global uint* claim,
                          __global const int* restrict bodyColor, int color, ORDER_ARGS)
{
    int i = (int)get_global_id(0);
    if (i < edge_count(counters, edgeCapacity))
        claim_edge(edges, edgeColor, i, claim, bodyColor, color, joint_level(counters, edgeCapacity, i, ORDER_PASS));
}

__kernel void color_assign(__global const BtgEdge* restrict edges, __global int* edgeColor, __global uint* counters,
                           int edgeCapacity, __global const uint* restrict claim, __global int* bodyColor, int color,
                           ORDER_ARGS)
{
    int i = (int)get_global_id(0);
    if (i < edge_count(counters, edgeCapacity))
        assign_edge(edges, edgeColor, i, counters, claim, bodyColor, color, joint_level(counters, edgeCapacity, i, ORDER_PASS));
}

/* Edges left after the rounds share the last color, which the solver runs serially. */
__kernel void color_finish(__global int* edgeColor, __global uint* counters, int edgeCapacity, int lastColor)
{
    int i = (int)get_global_id(0);
    if (i < edge_count(counters, edgeCapacity) && edgeColor[i] < 0) {
        edgeColor[i] = lastColor;
        atomic_inc(&counters[BTG_COUNTER_LEFTOVERS]);
    }
}

/* color_serial: a CPU device's batching in one work-item, the same colouring as the claim and
 * assign sub-rounds above (ColorConstraints tests): each sub-round's claims are the minimum
 * priority over the eligible edges whatever their order, and an edge takes the colour only if
 * it holds every dynamic body's claim, which no other edge's assignment in the same pass can
 * change. Cheaper on a CPU in three ways: one launch where the rounds took three a sub-round
 * (PoCL, cubes 8,000: 108 launches, 5.3 ms of a 60 ms step); only the edges that can still
 * take the colour visited: `active` holds the uncoloured edges (index, bodies, priority) in
 * index order, `cand` those a sub-round left eligible for the next (no body of theirs in the
 * colour); and claims stamped with their sub-round instead of reset: claim[b] is body b's
 * lowest bid, claim[numBodies + b] the sub-round it was made in (a stale stamp reads as no
 * claim). `lists` holds both lists, four ints an edge each. */
/* color_serial's bid of priority p for body b in sub-round r (a claim of an older sub-round is none) */
static void serial_bid(__global uint* restrict claim, __global uint* restrict stamp, int b, uint p, uint r)
{
    claim[b] = stamp[b] == r ? min(claim[b], p) : p;
    stamp[b] = r;
}
__kernel void color_serial(__global const BtgEdge* restrict edges, __global int* restrict edgeColor,
                           __global uint* counters, int edgeCapacity, __global const BtgBodyProps* restrict props,
                           __global uint* restrict claim, __global int* restrict bodyColor, int numBodies, int rounds,
                           __global int4* restrict lists, ORDER_ARGS)
{
    if (get_global_id(0) != 0) return;
    const int n = edge_count(counters, edgeCapacity);
    const int nc = (int)min(counters[BTG_COUNTER_CONTACTS], (uint)(edgeCapacity - numJoints));
    /* ordered joints stay out of the lists: each takes its level's colour at that colour's start */
    const int firstJoint = ordered ? nc : n, endJoint = ordered ? min(nc + numJoints, n) : n;
    __global uint* restrict stamp = claim + numBodies;
    __global int4* restrict active = lists;
    __global int4* restrict cand = lists + edgeCapacity;
    for (int b = 0; b < numBodies; ++b) {
        bodyColor[b] = reset_color(props, b);
        stamp[b] = NO_CLAIM;
    }
    int left = 0;
    for (int i = 0; i < n; ++i) {
        edgeColor[i] = -1;
        if (i < firstJoint || i >= endJoint) active[left++] = (int4)(i, edges[i].bodyA, edges[i].bodyB, (int)btgColorPriority(i));
    }
    int jointsLeft = endJoint - firstJoint;
    uint used = 0u;
    for (int color = 0; color < rounds && left + jointsLeft > 0; ++color) {
        for (int i = firstJoint; i < endJoint; ++i) {
            if (jointLevels[i - nc] != color) continue;
            edgeColor[i] = color;
            if (bodyColor[edges[i].bodyA] != BODY_FIXED) bodyColor[edges[i].bodyA] = color;
            if (bodyColor[edges[i].bodyB] != BODY_FIXED) bodyColor[edges[i].bodyB] = color;
            used = (uint)(color + 1);
            --jointsLeft;
        }
        /* Sub-round 0 over every uncoloured edge (each eligible: no body has this colour yet),
         * dropping those the last colour's later sub-rounds took; its losers are the next's
         * candidates. */
        uint r = (uint)(color * BTG_COLOR_SUB_ROUNDS);
        int kept = 0;
        for (int k = 0; k < left; ++k) {
            const int4 e = active[k];
            if (edgeColor[e.x] >= 0) continue;
            active[kept++] = e;
            /* a body an ordered joint took in this colour is not free (without joints none is) */
            if (bodyColor[e.y] == color || bodyColor[e.z] == color) continue;
            const uint p = (uint)e.w;
            if (bodyColor[e.y] != BODY_FIXED) serial_bid(claim, stamp, e.y, p, r);
            if (bodyColor[e.z] != BODY_FIXED) serial_bid(claim, stamp, e.z, p, r);
        }
        left = kept;
        __global int4* src = active;
        int nsrc = left;
        for (int sub = 0;; ++sub) {
            /* assign: an edge takes the colour if it holds each dynamic body's claim */
            int losers = 0;
            for (int k = 0; k < nsrc; ++k) {
                const int4 e = src[k];
                const int ca = bodyColor[e.y], cb = bodyColor[e.z];
                const uint p = (uint)e.w;
                /* out of the colour (a body in it): made no bid this sub-round, and the next
                 * sub-round's candidates leave it out (as the claim pass's body_free) */
                if (ca == color || cb == color) continue;
                if ((ca == BODY_FIXED || claim[e.y] == p) && (cb == BODY_FIXED || claim[e.z] == p)) {
                    edgeColor[e.x] = color;
                    if (ca != BODY_FIXED) bodyColor[e.y] = color;
                    if (cb != BODY_FIXED) bodyColor[e.z] = color;
                    used = (uint)(color + 1);
                } else {
                    cand[losers++] = e;
                }
            }
            if (sub + 1 == BTG_COLOR_SUB_ROUNDS || losers == 0) break;
            /* the next sub-round's claims: the losers whose bodies are both still out of the colour */
            r = (uint)(color * BTG_COLOR_SUB_ROUNDS + sub + 1);
            int eligible = 0;
            for (int k = 0; k < losers; ++k) {
                const int4 e = cand[k];
                const int ca = bodyColor[e.y], cb = bodyColor[e.z];
                if (ca == color || cb == color) continue;
                cand[eligible++] = e;
                const uint p = (uint)e.w;
                if (ca != BODY_FIXED) serial_bid(claim, stamp, e.y, p, r);
                if (cb != BODY_FIXED) serial_bid(claim, stamp, e.z, p, r);
            }
            src = cand;
            nsrc = eligible;
        }
    }
    int leftovers = 0;
    for (int k = 0; k < left; ++k)
        if (edgeColor[active[k].x] < 0) {
            edgeColor[active[k].x] = rounds;
            ++leftovers;
        }
    for (int i = firstJoint; i < endJoint; ++i)
        if (edgeColor[i] < 0) {
            edgeColor[i] = rounds;
            ++leftovers;
        }
    counters[BTG_COUNTER_LEFTOVERS] += (uint)leftovers;
    if (counters[BTG_COUNTER_COLORS_USED] < used) counters[BTG_COUNTER_COLORS_USED] = used;
}

/* color_resident: the whole batching in ONE launch (resident groups on GPUs, one group for
 * small scenes on CPUs): the same
 * init, claim/assign sub-rounds and finish as the per-launch kernels, with a grid barrier
 * (shared/grid_barrier.h) where those have a kernel boundary, so the coloring is identical.
 * Edge i is handled by the same work-item in every round (its color is read and written by
 * no other); claims and body colors are shared, through BTG_SHARED pointers and atomics.
 * claim holds 2 x numBodies claims and a word per sub-round after them (as colorConstraints
 * reserves it): the sub-rounds take the two halves in turn, each assign pass
 * resetting the half the next claim pass takes, so a sub-round has two grid barriers where the
 * per-launch kernels' reset makes three; and each claim pass notes in its sub-round's word
 * whether it met an uncolored edge, so the rounds stop at the first that met none (the host
 * colors two rounds more than the last step needed). H100, 2026-12-06: cubes 1,000 0.28 ms a
 * step before both. */
__kernel void color_resident(__global const BtgEdge* restrict edges, __global int* edgeColor, __global uint* counters,
                             int edgeCapacity, __global const BtgBodyProps* restrict props,
                             BTG_SHARED __global uint* claim, BTG_SHARED __global int* bodyColor, int numBodies,
                             int rounds, volatile __global BtgGridBarrier* bar, int spinLimit, ORDER_ARGS)
{
    __local int quit;
    __local int metUncolored;
    const int gid = (int)get_global_id(0), gsize = (int)get_global_size(0);
    const int n = edge_count(counters, edgeCapacity);
    BTG_SHARED __global uint* met = claim + 2 * numBodies; /* a word per sub-round */
    for (int i = gid; i < n; i += gsize) edgeColor[i] = -1;
    for (int b = gid; b < numBodies; b += gsize) {
        bodyColor[b] = reset_color(props, b);
        claim[b] = NO_CLAIM;
    }
    for (int r = gid; r < rounds * BTG_COLOR_SUB_ROUNDS; r += gsize) met[r] = 0u;
    int stop = btgGridBarrier(bar, spinLimit, &quit);
    for (int color = 0; color < rounds && !stop; ++color) {
        if (ordered) {
            /* the colour's ordered joints first, seen by every claim after the barrier; each
             * edge by the work-item that owns it in the other passes (i = gid mod gsize) */
            const int nc = (int)min(counters[BTG_COUNTER_CONTACTS], (uint)(edgeCapacity - numJoints));
            const int end = min(n, nc + numJoints);
            for (int i = nc <= gid ? gid : gid + (nc - gid + gsize - 1) / gsize * gsize; i < end; i += gsize)
                mark_joint(edges, edgeColor, i, counters, bodyColor, color, jointLevels[i - nc]);
            stop = btgGridBarrier(bar, spinLimit, &quit);
            if (stop) break;
        }
        for (int sub = 0; sub < BTG_COLOR_SUB_ROUNDS && !stop; ++sub) {
            const int r = color * BTG_COLOR_SUB_ROUNDS + sub;
            BTG_SHARED __global uint* cur = claim + (r & 1) * numBodies;
            BTG_SHARED __global uint* next = claim + ((r + 1) & 1) * numBodies;
            if (get_local_id(0) == 0) metUncolored = 0;
            barrier(CLK_LOCAL_MEM_FENCE);
            int mine = 0;
            for (int i = gid; i < n; i += gsize)
                mine |= claim_edge(edges, edgeColor, i, cur, bodyColor, color, joint_level(counters, edgeCapacity, i, ORDER_PASS));
            if (mine) metUncolored = 1;
            barrier(CLK_LOCAL_MEM_FENCE);
            if (get_local_id(0) == 0 && metUncolored) met[r] = 1u;
            stop = btgGridBarrier(bar, spinLimit, &quit);
            if (stop) break;
            /* every edge colored: the rounds left have nothing to do (every work-item reads the same word) */
            if (met[r] == 0u) {
                color = rounds;
                break;
            }
            for (int i = gid; i < n; i += gsize)
                assign_edge(edges, edgeColor, i, counters, cur, bodyColor, color, joint_level(counters, edgeCapacity, i, ORDER_PASS));
            for (int b = gid; b < numBodies; b += gsize) next[b] = NO_CLAIM;
            stop = btgGridBarrier(bar, spinLimit, &quit);
        }
    }
    if (stop) {
        if (gid == 0) atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_GRID_BARRIER_TIMEOUT);
        return;
    }
    for (int i = gid; i < n; i += gsize)
        if (edgeColor[i] < 0) {
            edgeColor[i] = rounds;
            atomic_inc(&counters[BTG_COUNTER_LEFTOVERS]);
        }
}
