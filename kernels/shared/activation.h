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

static inline float btgOwnTimer(float timer, BtgFloat4 v, BtgFloat4 w, BtgBodyProps p, float dt)
{
    if (p.flags & BTG_BODY_NEVER_SLEEP) return 0.0f;
    int slow = btgDot3(v, v) < p.sleepLinear * p.sleepLinear && btgDot3(w, w) < p.sleepAngular * p.sleepAngular;
    return slow ? timer + dt : 0.0f;
}

/* Whether body a (flags fa, own timer ta) wakes the sleeping body b it touches: a moving
 * dynamic body does (joining an active island), and so does any kinematic one (Bullet's
 * "kinematic objects don't merge islands, but wake up all connected objects"). */
static inline int btgWakes(uint fa, uint fb, float ta)
{
    if (!(fb & BTG_BODY_SLEEPING) || (fb & BTG_BODY_EXCLUDED)) return 0;
    if ((fa & BTG_BODY_KINEMATIC) && !(fa & (BTG_BODY_EXCLUDED | BTG_BODY_NO_RESPONSE))) return 1;
    return btgCanSleep(fa) && ta == 0.0f;
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
