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
    size_t size() const { return m_map.size() - m_dead.size(); }

private:
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
        long stamp;  // the last fill that named it (written by the parallel pass: atomically)
        unsigned ids[4];  // the feature id of each of its points (BTG_FEATURE_*)
    };
    using Node = std::pair<const Key, Entry>;  // a map node: its address stays while it is in the map
    // One report's manifold in Bullet's terms (orient: which side is body0, the key).
    struct Side {
        Key key;
        Node* node;    // the map's entry for key, null while it has none
        bool valid;    // both bodies still in the world
        bool swap;     // the report's B is Bullet's body0
        bool spheres;  // sphere–sphere (stock clears that manifold every step)
        const btCollisionShape* concaveA;  // the report's concave leaves (per-point triangles)
        const btCollisionShape* concaveB;
    };
    // The reports [first, last) of one manifold.
    struct Group {
        Node* entry;
        size_t first, last;
        bool spheres;
    };
    Side orient(const RowMap& rows, const BtgContactReport& r,
                const std::unordered_set<const btCollisionObject*>& removed) const;
    // One manifold's points from its reports (touches only that manifold: run in parallel).
    void refill(const Group& g, const BtgContactReport* reports);

    // Drops one map entry (and its place in m_byObject); the manifold is the caller's to release.
    void forget(Node* node);

    std::unordered_map<Key, Entry, KeyHash> m_map;
    // Every entry by each of its two bodies, so that removing a body costs its own manifolds,
    // not a walk of the whole map (an app clearing a level removes thousands).
    std::unordered_map<const btCollisionObject*, std::vector<Node*>> m_byObject;
    // The entries the last fill named or kept: the only ones this fill can find stale.
    std::vector<Node*> m_live;
    std::vector<Node*> m_nextLive;
    std::vector<unsigned char> m_staleFlag;
    // Entries whose body left (manifold released at once, node kept until the next fill so that
    // m_live never names a freed node); a key found again is revived with a new manifold.
    std::unordered_set<Node*> m_dead;
    long m_stamp = 0;
    std::vector<Side> m_sides;    // per report of the current fill
    std::vector<Group> m_groups;
    std::vector<BtgContactReport> m_scratch;
};

}  // namespace btgpu
