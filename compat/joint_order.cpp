// joint_order.cpp — stock's solve order of the world's joints (joint_order.h).
#include "joint_order.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <unordered_map>

namespace btgpu {

namespace {
// A body that takes part in islands (stock's isStaticOrKinematicObject test: static and
// kinematic bodies have island tag -1; btTypedConstraint's fixed body is static).
bool inIslands(const btCollisionObject& o) { return !o.isStaticOrKinematicObject(); }

// One entry of the sort: the constraint's island key and its index. Sorted with Bullet's own
// quickSort (the template from its header) and the key compared as
// btSortConstraintOnIslandPredicate compares island ids, so the permutation is stock's.
struct Keyed {
    int key;
    int index;
};
struct ByKey {
    bool operator()(const Keyed& a, const Keyed& b) const { return a.key < b.key; }
};
}  // namespace

std::vector<int> stockJointOrder(const btDiscreteDynamicsWorld& world)
{
    const int n = world.getNumConstraints();
    // The joints' bodies in islands, numbered densely for the union-find.
    std::unordered_map<const btCollisionObject*, int> id;
    std::vector<const btCollisionObject*> objects;
    auto idOf = [&](const btCollisionObject* o) {
        auto it = id.emplace(o, int(objects.size()));
        if (it.second) objects.push_back(o);
        return it.first->second;
    };
    for (int i = 0; i < n; ++i) {
        const btTypedConstraint* c = world.getConstraint(i);
        if (inIslands(c->getRigidBodyA())) idOf(&c->getRigidBodyA());
        if (inIslands(c->getRigidBodyB())) idOf(&c->getRigidBodyB());
    }
    // btUnionFind's unite: the first set's root points at the second's (USE_PATH_COMPRESSION),
    // so a set's root, and with it its island id, depends on the order of the unions: the
    // enabled joints between two island bodies, in the world's order (calculateSimulationIslands).
    std::vector<int> parent(objects.size());
    for (size_t k = 0; k < parent.size(); ++k) parent[k] = int(k);
    auto find = [&](int x) {
        while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
        return x;
    };
    for (int i = 0; i < n; ++i) {
        const btTypedConstraint* c = world.getConstraint(i);
        if (!c->isEnabled() || !inIslands(c->getRigidBodyA()) || !inIslands(c->getRigidBodyB())) continue;
        const int a = find(id[&c->getRigidBodyA()]), b = find(id[&c->getRigidBodyB()]);
        if (a != b) parent[size_t(a)] = b;
    }
    // The island id stock gives a body is its root's index among the world's island bodies,
    // which orders as the root's place in the collision object array.
    btAlignedObjectArray<Keyed> sorted;
    sorted.resize(n);
    for (int i = 0; i < n; ++i) {
        const btTypedConstraint* c = world.getConstraint(i);
        const btCollisionObject* a = &c->getRigidBodyA();
        const btCollisionObject* b = &c->getRigidBodyB();
        // btGetConstraintIslandId: body A's island unless A is out of the islands (tag -1)
        const btCollisionObject* o = inIslands(*a) ? a : inIslands(*b) ? b : nullptr;
        sorted[i].key = o ? objects[size_t(find(id[o]))]->getWorldArrayIndex() : -1;
        sorted[i].index = i;
    }
    sorted.quickSort(ByKey());
    std::vector<int> order(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) order[size_t(k)] = sorted[k].index;
    return order;
}

std::vector<int> stockJointLevels(const btDiscreteDynamicsWorld& world)
{
    const int n = world.getNumConstraints();
    if (n < 2) return {};
    // Quick out: no island body in two joints, no order to keep.
    std::unordered_map<const btCollisionObject*, int> uses;
    bool shared = false;
    for (int i = 0; i < n && !shared; ++i) {
        const btTypedConstraint* c = world.getConstraint(i);
        for (const btCollisionObject* o : {static_cast<const btCollisionObject*>(&c->getRigidBodyA()),
                                           static_cast<const btCollisionObject*>(&c->getRigidBodyB())})
            if (inIslands(*o) && ++uses[o] > 1) shared = true;
    }
    if (!shared) return {};
    // In stock's order, each joint one level above the last level any of its bodies took.
    std::unordered_map<const btCollisionObject*, int> last;
    std::vector<int> levels(size_t(n), 0);
    for (int i : stockJointOrder(world)) {
        const btTypedConstraint* c = world.getConstraint(i);
        const btCollisionObject* a = &c->getRigidBodyA();
        const btCollisionObject* b = &c->getRigidBodyB();
        int level = 0;
        for (const btCollisionObject* o : {a, b}) {
            if (!inIslands(*o)) continue;
            auto it = last.find(o);
            if (it != last.end()) level = std::max(level, it->second + 1);
        }
        for (const btCollisionObject* o : {a, b})
            if (inIslands(*o)) last[o] = level;
        levels[size_t(i)] = level;
    }
    return levels;
}

}  // namespace btgpu
