// ghost_objects.h — ghost objects (btGhostObject, btPairCachingGhostObject) on the GPU path:
// while the world holds one, Bullet's own broadphase pair update runs on the host at the start
// of each internal step, as stock's performDiscreteCollisionDetection runs it, so every ghost's
// overlapping objects (and the app's ghost callbacks) are stock's. On the device a ghost is a
// collider only when it has contact response (compat/body_rows.cpp).
#pragma once
#include <vector>

class btCollisionObject;
class btDbvtBroadphase;
class btDiscreteDynamicsWorld;

namespace btgpu {

class RowMap;

// The world's ghost objects, in collision-object order (read when something is added or removed).
std::vector<const btCollisionObject*> findGhosts(const btDiscreteDynamicsWorld& world);

// Stock's broadphase work at the start of an internal step of dt: each dynamic body's
// interpolation transform set to its predicted one (predictUnconstraintMotion, the velocities
// left as they were), then updateAabbs and computeOverlappingPairs, whose pair callbacks fill
// the ghosts' lists.
void updateBroadphaseAsStock(btDiscreteDynamicsWorld& world, float dt);

// The same AABBs (predicted motion included, the Dbvt leaves fattened as stock's), but only the
// ghosts' pairs updated, from Bullet's own tree: each ghost's leaf against both trees, new pairs
// added to the pair cache (its ghost callback fills the list, as stock's), pairs whose leaves no
// longer overlap removed at once (stock's lazy cleanup takes up to ~10 steps). For big worlds,
// where the whole pair update is stock's dearest step; the other pairs are left as they were.
void updateGhostPairsFromTree(btDiscreteDynamicsWorld& world, btDbvtBroadphase& dbvt,
                              const std::vector<const btCollisionObject*>& ghosts, float dt);

// After the broadphase update: per row, whether the body is in a broadphase pair with a ghost
// that merges simulation islands (contact response, neither static nor kinematic) and merges
// islands itself. Stock unites the two into an island the ghost (never deactivated) keeps awake,
// and wakes the body if it slept; the row is held awake (BTG_BODY_NEVER_SLEEP) for this step, and
// a sleeping body is woken here (WANTS_DEACTIVATION, as stock's island manager leaves it).
void heldAwakeByGhosts(btDiscreteDynamicsWorld& world, const RowMap& rows, std::vector<char>* held);

}  // namespace btgpu
