// update_activation.h — Stage: update_activation (kernels/update_activation.cl). Bullet's
// deactivation on the device: per-body timers, island minimum spread over the constraint
// graph's edges (contacts, and any constraint kind that adds edges)
// (`rounds` hops per substep, double-buffered so the result is order-free), sleep when the
// island has been slow for `deactivationTime` s, wake when a moving body touches a sleeper.
// Reads linVel, angVel, props, edges, counters[kEdgeCount]. Writes sleepTime, islandTime, wake,
// props.flags (SLEEPING), linVel/angVel (zeroed on falling asleep), sleepState.
// deactivationTime 0 (gDisableDeactivation) turns sleeping off.
#pragma once
#include "world/device_world.h"

namespace btgpu {
void updateActivation(DeviceWorld& w, float dt, float deactivationTime, int rounds = 4);
// Before the contacts' rows are made: a sleeping body a moving one touches wakes now, so this
// step's solve moves it (stock activates the island before its solve), and so does every
// sleeping body the joints join to an awake or woken one. Reads contacts,
// counters[kContactCount], joints, props, sleepTime. Writes props.flags, sleepTime, sleepState,
// wake.
void wakeTouched(DeviceWorld& w);
}
