// contact_callbacks.h — Bullet's gContactAddedCallback on the GPU path: for pairs with a
// CF_CUSTOM_MATERIAL_CALLBACK body, each internal step stops after its contacts are found; the
// host builds each point as btManifoldResult::addContactPoint would (Bullet's body order, local
// and world points, combined coefficients, part ids), calls the app's callback with stock's
// wrappers (a compound's child shape and transform, a mesh's btTriangleShape), and sends back
// what it changed: friction, restitution, normal, points and distance, used by that step's solve.
#pragma once
#include "manifold_sync.h"
#include "row_map.h"
#include "shape_tables.h"
#include "btgpu/Config.h"
#include "stages/contact_callbacks.h"

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <string>
#include <unordered_set>
#include <vector>

class btCollisionObject;
class btDiscreteDynamicsWorld;

namespace btgpu {

class ContactCallbacks {
public:
    // The app's callbacks that run between a step's contacts and its solve: gContactAddedCallback
    // while a body has CF_CUSTOM_MATERIAL_CALLBACK, gContactProcessedCallback, and any custom
    // gCalculateCombined*Callback. The manifold events (started, ended, destroyed) come from the
    // dispatcher fill at each internal step (manifold_sync.h).
    static bool customMaterials(const btDiscreteDynamicsWorld& world);
    static bool customCombiners();
    static bool wanted(const btDiscreteDynamicsWorld& world);
    static bool events();  // gContactStarted/Ended/Processed/DestroyedCallback
    // The callbacks that run before the solve, as a value: a refusal holds while they are the same.
    struct Set {
        ContactAddedCallback added;
        ContactProcessedCallback processed;
        CalculateCombinedCallback friction, restitution, rolling, spinning;
        bool operator==(const Set& o) const
        {
            return added == o.added && processed == o.processed && friction == o.friction &&
                   restitution == o.restitution && rolling == o.rolling && spinning == o.spinning;
        }
    };
    static Set current();
    // Why they cannot be served on the GPU path while wanted ("" when they can): with
    // Config::internalSubsteps > 1 they would be called once per device substep, more often than
    // stock. (Support-function shapes' persistent manifolds name the point each substep added:
    // the added callback is called for it alone, as stock's convex–convex algorithm.)
    static std::string unservedReason(const btDiscreteDynamicsWorld& world, const Config& config);
    // The host's part between the contacts and the solve. False when a change the callback made
    // cannot be carried by the device's contacts (reason() says which): the step must run on the
    // CPU path instead.
    // The points' user data come from and go to `sync` (the app's manifolds): a point that
    // continues one keeps its user data, what the callbacks set reaches the next fill.
    bool run(DeviceWorld& w, const RowMap& rows, const std::unordered_set<const btCollisionObject*>& removed,
             ManifoldSync& sync);
    // An app's overlap filter callback: Bullet's broadphase, run on the host at the step's start
    // (updateBroadphaseAsStock), asked it for each new pair as stock's does; the device's pairs
    // its pair cache does not hold make no contact. True while the world has one.
    static bool overlapFilter(btDiscreteDynamicsWorld& world);
    void keepStockPairs(DeviceWorld& w, const RowMap& rows, btDiscreteDynamicsWorld& world);
    const std::string& reason() const { return m_reason; }
    // Calls made in the last run (points passed to the callback).
    long calls() const { return m_calls; }

private:
    std::string m_reason;
    long m_calls = 0;
    std::vector<GatheredManifold> m_changed;
    std::vector<BtgContactMaterial> m_materials;
};

}  // namespace btgpu
