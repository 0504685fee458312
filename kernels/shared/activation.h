/* activation.h — Bullet's deactivation rules as shared functions: a body's own timer
 * (btRigidBody::updateDeactivation) and its island's (the least timer among the bodies the
 * constraint graph's edges, contacts and any other kind, connect it to; an island sleeps when every body in it has been slow for
 * gDeactivationTime, as btSimulationIslandManager decides). Timers are non-negative floats,
 * compared as their uint bits so atomic_min orders them exactly. */
#ifndef BTG_ACTIVATION_H
#define BTG_ACTIVATION_H
#include "types.h"

#define BTG_NEVER_UINT 0x7f800000u /* +inf: takes no part in an island */

/* Bodies that can fall asleep and that make up islands: dynamic, awake, in the simulation. */
static inline int btgCanSleep(uint flags)
{
    return (flags & BTG_BODY_DYNAMIC) && !(flags & (BTG_BODY_SLEEPING | BTG_BODY_EXCLUDED));
}

/* Bodies whose contacts unite islands (mergesSimulationIslands: not static, kinematic or
 * CF_NO_CONTACT_RESPONSE). A no-response body's contacts neither unite nor wake: it sleeps by
 * its own timer and touches nothing awake, as in stock. */
static inline int btgMergesIslands(uint flags)
{
    return btgCanSleep(flags) && !(flags & BTG_BODY_NO_RESPONSE);
}

static inline float btgOwnTimer(float timer, BtgFloat4 v, BtgFloat4 w, BtgBodyProps p, float dt)
{
    if (p.flags & BTG_BODY_NEVER_SLEEP) return 0.0f;
    int slow = btgDot3(v, v) < p.sleepLinear * p.sleepLinear && btgDot3(w, w) < p.sleepAngular * p.sleepAngular;
    return slow ? timer + dt : 0.0f;
}

/* Whether body a (flags fa, own timer ta) wakes the sleeping body b it touches: a moving
 * dynamic body does (joining an active island), and so does any kinematic one with contact
 * response (Bullet's "kinematic objects don't merge islands, but wake up all connected
 * objects"). Only dynamic bodies wake (activate() leaves static and kinematic ones), and a
 * no-response body wakes nothing (it merges no island). */
static inline int btgWakes(uint fa, uint fb, float ta)
{
    if (!(fb & BTG_BODY_SLEEPING) || (fb & BTG_BODY_EXCLUDED) || !(fb & BTG_BODY_DYNAMIC)) return 0;
    if ((fa & BTG_BODY_KINEMATIC) && !(fa & (BTG_BODY_EXCLUDED | BTG_BODY_NO_RESPONSE))) return 1;
    return btgMergesIslands(fa) && !(fb & BTG_BODY_NO_RESPONSE) && ta == 0.0f;
}

/* Whether a joint from awake dynamic body a wakes the sleeping body b it links: stock unites a
 * joint's two dynamic bodies into one island when either is active, and an island with an
 * active body wakes whole, however slow that body is. Kinematic and static bodies merge no
 * islands. */
static inline int btgJointWakes(uint fa, uint fb)
{
    if (!(fb & BTG_BODY_SLEEPING) || (fb & BTG_BODY_EXCLUDED) || !(fb & BTG_BODY_DYNAMIC)) return 0;
    return btgCanSleep(fa);
}

#endif
