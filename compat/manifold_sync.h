// manifold_sync.h — the app's own dispatcher holds, on the GPU path, the contact manifolds
// stock Bullet's collision algorithms would hold: one btPersistentManifold per touching
// (body, body) — per compound child pair, one per convex–mesh pair — taken from and given back
// to the dispatcher's pool, filled from the device's contact reports (report_contacts).
#pragma once
#include "manifold_table.h"
#include "row_map.h"
#include "stages/sync_bodies.h"

#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

class btCollisionObject;
class btCollisionShape;
class btCollisionWorld;
class btDispatcher;
class btManifoldPoint;
class btPersistentManifold;
class btOverlappingPairCache;

namespace btgpu {

// A point on a concave side: its triangle's (part id, index) from its feature id (the
// triangle's key, btgTriangleKey), as Bullet's per-point m_partId / m_index of that side.
void triangleOfFeature(const btCollisionShape* concave, unsigned key, int* partId, int* index);

class ManifoldSync {
public:
    // Every manifold this call's reports name is created or refilled; those of pairs no longer
    // touching are released, except where both bodies sleep (stock keeps those as they were).
    // `removed`: objects that left inside this call (their rows still name them).
    // beforeEvents: called once the manifolds are refilled, before the app's contact callbacks
    // and before any body's activation is read (a job run beside the fill is waited for there).
    void fill(btDispatcher* dispatcher, const RowMap& rows, const BodyReadback& rb,
              const std::unordered_set<const btCollisionObject*>& removed,
              const std::function<void()>& beforeEvents = {});
    // All given back (the CPU path's algorithms make their own; the switch turned off; rebuild).
    // Their contacts do not end for the app (no gContactEndedCallback: the CPU path's manifolds
    // take them on); points' user data go to gContactDestroyedCallback, as they leave the app.
    void releaseAll(btDispatcher* dispatcher);
    // Before Bullet's own step takes over (manifold_handover.cpp): each manifold with points of
    // two convex, non-compound bodies goes to the algorithm stock's near callback makes for
    // the pair (made now, as that callback makes it), whose manifold takes its points as they
    // are (lifetimes, impulses, user data), so the contact continues there with no ended or
    // started event, as on stock; returns how many were handed over. Those stock's algorithm
    // makes lazily (GJK pairs) and sphere pairs (cleared every step) are not. Gives back every
    // manifold of this fill's (releaseAll) on the way.
    int handToStock(btCollisionWorld& world);
    // The other way, back on the GPU path before the CPU path's algorithms are freed: each of
    // their manifolds with points of two convex, non-compound bodies becomes this fill's, its
    // points moved over as they are (the device continues them: seed_contacts.h names them by
    // slot), so freeing the algorithms ends no contact and destroys no user data, and the
    // contact goes on with no started event; returns how many were taken.
    int takeFromStock(btDispatcher* dispatcher);
    // The transforms the device collides the next fill's pairs at: each row's, as the host holds
    // them before a device call of one substep. Stock's refreshContactPoints keeps a manifold's
    // old points its detector did not replace while they stay within the breaking threshold at
    // those transforms; without them (a call of several device substeps: only the last one's
    // contacts come back) the fill keeps only the device's points.
    // staticLeavesFattened: stock's world updates every AABB each step (getForceUpdateAllAabbs,
    // its default), so a static body's Dbvt leaf is fattened by the leaf margin as a moving one's.
    void noteCollidedAt(const RowMap& rows, bool staticLeavesFattened);
    void forgetCollidedAt() { m_collidedAtValid = false; }
    // Config::stockEmptyManifolds: the pairs stock's dispatcher has collided, from its pair cache
    // just updated as stock's at an internal step's start (pair_manifolds.cpp). The next fill
    // holds a manifold (empty where the device found no points) for each, and gives back those
    // of pairs that left. Without a call before a fill, only manifolds with points are held.
    void notePairs(btDispatcher* dispatcher, btOverlappingPairCache* cache, const RowMap& rows,
                   const std::unordered_set<const btCollisionObject*>& removed);
    // The same from the device's leaf pairs (rows; leaf_pairs.h), noted after the step's device
    // call and before its write-back: the bodies still hold the step's start (transforms,
    // activation), what stock's near callback saw. The whole list after the cache started afresh;
    // then only the pairs that joined and left it (the cost follows what changed).
    void noteLeafPairs(btDispatcher* dispatcher, const std::vector<BtgPair>& pairs, const RowMap& rows,
                       const std::unordered_set<const btCollisionObject*>& removed);
    void noteLeafChanges(btDispatcher* dispatcher, const std::vector<BtgPair>& joined, const std::vector<BtgPair>& left,
                         const RowMap& rows, const std::unordered_set<const btCollisionObject*>& removed);
    // Those of an object leaving the world (stock: removeRigidBody → cleanProxyFromPairs).
    void removed(btDispatcher* dispatcher, const btCollisionObject* object);
    size_t size() const { return m_map.size() - m_dead.size(); }

    // A device point as the app's callbacks saw it before the solve (contact_callbacks.cpp): its
    // device manifold (bodies and sub-shape keys as the device names them), feature id and
    // place; the next fill gives the manifold point made of it that user data.
    struct PointKey {
        int bodyA, bodyB, indexA, indexB;
        unsigned featureId;
        int k;
        bool operator==(const PointKey& o) const
        {
            return bodyA == o.bodyA && bodyB == o.bodyB && indexA == o.indexA && indexB == o.indexB &&
                   featureId == o.featureId && k == o.k;
        }
    };
    struct PointKeyHash {
        size_t operator()(const PointKey& p) const
        {
            size_t h = size_t(p.bodyA) * 1000003u + size_t(p.bodyB);
            h = h * 131u + size_t(p.indexA) * 31u + size_t(p.indexB);
            return (h * 1000003u + p.featureId) * 5u + size_t(p.k);
        }
    };
    // What the callbacks left on a point before the solve: its user data and combined
    // coefficients (those the solve used), given to the manifold point the next fill makes of it;
    // moved: a callback changed its points or distance (continued() tells the next step).
    struct PointState {
        void* userData;
        btScalar friction, restitution;
        bool moved;
    };
    void setPointState(const PointKey& point, const PointState& state) { m_pending[point] = state; }

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
        // Mixed to every bit (splitmix64's finaliser): the table takes the low bits of the hash,
        // and objects' addresses share their low ones.
        size_t operator()(const Key& k) const
        {
            uint64_t h = uint64_t(reinterpret_cast<uintptr_t>(k.body0)) * 0x9E3779B97F4A7C15ull;
            h ^= uint64_t(reinterpret_cast<uintptr_t>(k.body1)) + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2);
            h ^= ((uint64_t(uint32_t(k.sub0)) << 32) | uint32_t(k.sub1)) * 0xC2B2AE3D27D4EB4Full;
            h ^= h >> 30;
            h *= 0xBF58476D1CE4E5B9ull;
            h ^= h >> 27;
            h *= 0x94D049BB133111EBull;
            return size_t(h ^ (h >> 31));
        }
    };
    struct Entry {
        btPersistentManifold* manifold;
        long stamp;  // the last fill that named it (written by the parallel pass: atomically)
        unsigned ids[4];  // the feature id of each of its points (BTG_FEATURE_*)
        bool moved[4];    // each point's PointState::moved as it was filled
        bool persistent = false;  // its last fill was a device persistent manifold (box and GJK pairs)
    };
    using Table = ManifoldTable<Key, Entry, KeyHash>;
    using Node = Table::Node;  // its address stays while it is in the table
    // One report's manifold in Bullet's terms (orient: which side is body0, the key).
    struct Side {
        Key key;
        Node* node;    // the map's entry for key, null while it has none
        bool held;     // node has a manifold (as the fill's lookups found it: none loses it before the refill)
        bool valid;    // both bodies still in the world
        bool swap;     // the report's B is Bullet's body0
        bool spheres;  // sphere–sphere (stock clears that manifold every step)
        const btCollisionShape* concaveA;  // the report's concave leaves (per-point triangles)
        const btCollisionShape* concaveB;
        int refreshes;  // refreshContactPoints a step on stock (refreshesPerStep)
    };
    // How often stock refreshes the manifold of a pair in a step (each ages its points by one and
    // calls gContactProcessedCallback): twice where a body is a compound (its algorithm refreshes
    // every child manifold before the children collide, then each child's own algorithm refreshes
    // its manifold), else once.
    static int refreshesPerStep(const btCollisionObject* body0, const btCollisionObject* body1);
    // One device manifold's sides (bodies and sub-shape keys as the device names them).
    static Side orient(const RowMap& rows, int bodyA, int bodyB, int indexA, int indexB,
                       const std::unordered_set<const btCollisionObject*>& removed);
    // The app's manifold point (as the last fill left it) that a point of this side's manifold
    // continues (as the fill matches them: same feature and sub-shape, else the nearest in
    // body0's frame within the breaking threshold), nullptr when none; *moved: whether a
    // callback changed that point's geometry before the solve that made it. `identities`: the
    // feature ids are the points' identities (a GJK pair's persistent manifold), which match
    // wherever the point has gone in A's frame (a rolling body's point turns with it).
    const btManifoldPoint* continued(const Side& side, unsigned featureId, int index0, int partId1, int index1,
                                     const btVector3& localA, bool* moved = nullptr, bool identities = false) const;
    // The app's manifold of this side as the last fill left it, nullptr when none (the callbacks
    // before the solve may set its old points' user data and coefficients: the fill keeps them).
    btPersistentManifold* manifold(const Side& side) const
    {
        const Node* node = m_map.find(side.key);
        return node ? node->second.manifold : nullptr;
    }

private:
    // The reports [first, last) of one manifold.
    struct Group {
        Node* entry;
        size_t first, last;
        int row0, row1;  // the rows of Bullet's body0 and body1
        bool spheres;
        bool fresh;   // made by this fill: its contact starts (gContactStartedCallback)
        int before;   // points it held before this fill
        std::vector<void*> dropped;  // user data of its points that did not continue
    };
    // One manifold's points from its reports (touches only that manifold: run in parallel).
    void refill(Group& g, const BtgContactReport* reports);
    // The app's manifold events of the groups just refilled, serially in group order.
    void contactEvents();

    // A manifold no report named while a body of it is awake: refreshed as stock's algorithm
    // refreshes it; whether points remain (else the caller releases it).
    bool keepsOldPoints(Node* node, const RowMap& rows);
    // Drops one map entry (and its place in m_byObject); the manifold is the caller's to release.
    void forget(Node* node);
    // Config::stockEmptyManifolds, in the fill: whether a manifold the device did not name
    // stays (its pair still stock's), and empty manifolds for the noted pairs that have none.
    bool stockHolds(const Key& key) const { return m_wantedSet.find(key) != nullptr; }
    void holdStockPairs(btDispatcher* dispatcher, const std::unordered_set<const btCollisionObject*>& removed);
    // One broadphase pair: its objects in the cache's order and its id (the proxies' unique ids).
    struct StockPair {
        const btCollisionObject* a;
        const btCollisionObject* b;
        unsigned long long id;
    };
    void notePairList(btDispatcher* dispatcher, bool valid, const std::vector<StockPair>& pairs, const RowMap& rows,
                      const std::unordered_set<const btCollisionObject*>& removed);
    void notePairChanges(btDispatcher* dispatcher, const std::vector<StockPair>& joined,
                         const std::vector<unsigned long long>& left, const RowMap& rows,
                         const std::unordered_set<const btCollisionObject*>& removed);
    // The manifold keys of a pair's algorithm as its collision this step leaves them.
    std::vector<Key> algorithmKeys(const btCollisionObject* a, const btCollisionObject* b, const RowMap& rows,
                                   const std::unordered_set<const btCollisionObject*>& removed) const;
    // Pairs noted but never collided (both bodies asleep since they joined), and those with a
    // compound side, by id (notePairChanges looks at these each step).
    std::unordered_map<unsigned long long, StockPair> m_uncollided;
    std::unordered_map<unsigned long long, StockPair> m_compoundPairs;

    Table m_map;
    std::vector<btTransform> m_collidedAt;  // per row (noteCollidedAt)
    bool m_collidedAtValid = false;
    bool m_staticLeavesFattened = true;
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
    std::vector<size_t> m_hashes;  // each side's key's hash
    std::vector<Group> m_groups;
    std::vector<size_t> m_starts;  // each group's first report
    std::vector<std::vector<size_t>> m_startsIn, m_unheldIn;  // per chunk of the group passes
    std::vector<BtgContactReport> m_scratch;
    std::unordered_map<PointKey, PointState, PointKeyHash> m_pending;  // for the next fill
    // Config::stockEmptyManifolds (notePairs): the manifold keys of each pair stock's dispatcher
    // has collided, by the pair's proxy ids (an algorithm lives as long as its pair), and all
    // of them in the pair cache's order (the order empty manifolds are made in).
    std::unordered_map<unsigned long long, std::vector<Key>> m_stockPairs;
    std::vector<Key> m_wanted;
    ManifoldTable<Key, char, KeyHash> m_wantedSet;  // as a set
    bool m_wantedValid = false;
};

}  // namespace btgpu
