// ccd_steps.h — Bullet's continuous collision detection (setCcdMotionThreshold) on the GPU path,
// step by step. Stock sweeps a sphere of a body's swept radius along its motion twice a step
// (createPredictiveContacts before the solve, with the velocity the step starts with;
// integrateTransforms after it, with the solved one) when the body moves farther than its
// threshold; only a hit changes anything (a predictive contact, a clamped motion). So a step in
// which no sweep hits is stock's on the GPU path, and a step in which one would hit runs on
// Bullet's own CPU path (before the device's step, or instead of it: its results are dropped).
#pragma once
#include <LinearMath/btVector3.h>

#include <functional>
#include <string>
#include <vector>

class btDiscreteDynamicsWorld;
class btRigidBody;

namespace btgpu {

// Whether any of `bodies` (active, dynamic, convex, a motion threshold set) moving over dt with
// velocity(body) from where it is now would have stock's sweep hit something; *why names the
// first such body and what it hits.
bool ccdSweepHits(btDiscreteDynamicsWorld& world, const std::vector<btRigidBody*>& bodies, float dt,
                  const std::function<btVector3(btRigidBody*)>& velocity, std::string* why);

// The velocity stock's createPredictiveContacts moves a body with: its own, damped for dt as
// predictUnconstraintMotion damps it (the body is left as it was).
btVector3 dampedVelocity(btRigidBody* body, float dt);

}  // namespace btgpu
