// ghost_objects.h — ghost objects (btGhostObject, btPairCachingGhostObject) on the GPU path:
// they are no device rows; while the world holds one, Bullet's own broadphase pair update runs
// on the host at the start of each internal step, as stock's performDiscreteCollisionDetection
// runs it, so every ghost's overlapping objects (and the app's ghost callbacks) are stock's.
#pragma once
#include <string>
#include <vector>

class btCollisionObject;
class btDiscreteDynamicsWorld;

namespace btgpu {

// The world's ghost objects, in collision-object order (read when something is added or removed).
std::vector<const btCollisionObject*> findGhosts(const btDiscreteDynamicsWorld& world);

// Per step: a ghost with contact response (a character's ghost) is a fixed collider that merges
// simulation islands in stock; the GPU path serves it only while no dynamic body with contact
// response could meet it (none in the world), and names it otherwise.
std::string ghostReason(const btDiscreteDynamicsWorld& world, const std::vector<const btCollisionObject*>& ghosts);

// Stock's broadphase work at the start of an internal step of dt: each dynamic body's
// interpolation transform set to its predicted one (predictUnconstraintMotion, the velocities
// left as they were), then updateAabbs and computeOverlappingPairs, whose pair callbacks fill
// the ghosts' lists.
void updateBroadphaseAsStock(btDiscreteDynamicsWorld& world, float dt);

}  // namespace btgpu
