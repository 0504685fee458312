// manifold_sync.h — the app's own dispatcher holds, on the GPU path, the contact manifolds
// stock Bullet's collision algorithms would hold: one btPersistentManifold per touching
// (body, body) — per compound child pair, one per convex–mesh pair — taken from and given back
// to the dispatcher's pool, filled from the device's contact reports (report_contacts).
#pragma once
#include "row_map.h"
#include "stages/sync_bodies.h"

#include <cstddef>
#include <unordered_map>
#include <unordered_set>
#include <vector>

class btCollisionObject;
class btCollisionShape;
class btDispatcher;
class btPersistentManifold;

namespace btgpu {

// A point on a concave side: its triangle's (part id, index) from its feature id (the
// triangle's key, btgTriangleKey), as Bullet's per-point m_partId / m_index of that side.
void triangleOfFeature(const btCollisionShape* concave, unsigned key, int* partId, int* index);

class ManifoldSync {
public:
    // Every manifold this call's reports name is created or refilled; those of pairs no longer
    // touching are released, except where both bodies sleep (stock keeps those as they were).
    // `removed`: objects that left inside this call (their rows still name them).
    void fill(btDispatcher* dispatcher, const RowMap& rows, const BodyReadback& rb,
              const std::unordered_set<const btCollisionObject*>& removed);
    // All given back (the CPU path's algorithms make their own; the switch turned off; rebuild).
    void releaseAll(btDispatcher* dispatcher);
    // Those of an object leaving the world (stock: removeRigidBody → cleanProxyFromPairs).
    void removed(btDispatcher* dispatcher, const btCollisionObject* object);
    size_t size() const { return m_map.size(); }

    struct Key {
        const btCollisionObject* body0;
        const btCollisionObject* body1;
        int sub0, sub1;  // compound child of each side, -1 for the whole shape or a concave side
        bool operator==(const Key& k) const
        {
            return body0 == k.body0 && body1 == k.body1 && sub0 == k.sub0 && sub1 == k.sub1;
        }
    };
    struct KeyHash {
        size_t operator()(const Key& k) const
        {
            size_t h = std::hash<const void*>()(k.body0) * 31 + std::hash<const void*>()(k.body1);
            return h * 1000003u + size_t(k.sub0) * 131u + size_t(k.sub1);
        }
    };
    struct Entry {
        btPersistentManifold* manifold;
        long stamp;  // the last fill that named it
        unsigned ids[4];  // the feature id of each of its points (BTG_FEATURE_*)
    };
    // One report's manifold in Bullet's terms (orient: which side is body0, the key).
    struct Side {
        Key key;
        bool valid;    // both bodies still in the world
        bool swap;     // the report's B is Bullet's body0
        bool spheres;  // sphere–sphere (stock clears that manifold every step)
        const btCollisionShape* concaveA;  // the report's concave leaves (per-point triangles)
        const btCollisionShape* concaveB;
    };
    // One device manifold's sides (bodies and sub-shape keys as the device names them).
    static Side orient(const RowMap& rows, int bodyA, int bodyB, int indexA, int indexB,
                       const std::unordered_set<const btCollisionObject*>& removed);

private:
    // The reports [first, last) of one manifold.
    struct Group {
        std::pair<const Key, Entry>* entry;
        size_t first, last;
        bool spheres;
    };
    // One manifold's points from its reports (touches only that manifold: run in parallel).
    void refill(const Group& g, const BtgContactReport* reports);

    std::unordered_map<Key, Entry, KeyHash> m_map;
    long m_stamp = 0;
    std::vector<Side> m_sides;    // per report of the current fill
    std::vector<Group> m_groups;
    std::vector<BtgContactReport> m_scratch;
};

}  // namespace btgpu
