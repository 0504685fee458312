// gjk_fixture.h — the GJK narrowphase tests' world: Bullet's bodies and the same bodies as the
// device's rows (Fixture), the stage run on them (runDevice) and a manifold compared with the
// CPU reference's (expectSame). Shared by narrowphase_gjk_test.cpp and narrowphase_round_test.cpp.
#pragma once
#include "reference/narrowphase_gjk.h"
#include "shape_tables.h"
#include "shared/aabb.h"
#include "shared/gjk.h"
#include "shared/persistent_manifold.h"
#include "stages/find_pairs.h"
#include "stages/narrowphase.h"
#include "test_device.h"
#include "tolerances.h"

#include "../../compat/shape_tables.h"

#include <btBulletCollisionCommon.h>

#include <memory>
#include <string>
#include <vector>
#include <gtest/gtest.h>

namespace btgpu::test::gjk {

struct Body {
    btCollisionShape* shape;
    btTransform pose;
};

// Both worlds of one test: Bullet's objects and the same bodies as rows (shape rows from compat's
// own conversion).
struct Fixture {
    std::vector<std::unique_ptr<btCollisionShape>> shapes;
    std::vector<std::unique_ptr<btTriangleMesh>> meshes;
    std::vector<Body> bodies;
    std::vector<BtgPair> pairs;
    ::btgpu::ShapeTables tables;

    template <class S>
    S* own(S* s)
    {
        shapes.emplace_back(s);
        return s;
    }
    int body(btCollisionShape* shape, btVector3 origin, btVector3 axis = btVector3(0, 0, 1), btScalar angle = 0)
    {
        btTransform t;
        t.setIdentity();
        t.setOrigin(origin);
        t.setRotation(btQuaternion(axis.normalized(), angle));
        bodies.push_back({shape, t});
        return int(bodies.size()) - 1;
    }
    void pair(int a, int b) { pairs.push_back({a, b}); }

    // Rows as the device reads them.
    std::vector<BtgFloat4> pos, rot;
    std::vector<BtgBodyProps> props;
    ::btgpu::test::ShapeTables view;
    void build()
    {
        pos.clear();
        rot.clear();
        props.clear();
        for (const Body& b : bodies) {
            std::string why;
            BtgBodyProps p{};
            p.shape = tables.add(b.shape, &why);
            EXPECT_GE(p.shape, 0) << why;
            p.flags = BTG_BODY_DYNAMIC;
            props.push_back(p);
            const btVector3& o = b.pose.getOrigin();
            const btQuaternion q = b.pose.getRotation();
            pos.push_back(btgMake4(o.x(), o.y(), o.z(), 0));
            rot.push_back(btgMake4(q.x(), q.y(), q.z(), q.w()));
        }
        view.shapes = tables.shapes;
        view.vertices = tables.vertices;
        view.faces = tables.faces;
        view.indices = tables.indices;
        view.edges = tables.edges;
    }
    PairKinds kinds() const
    {
        PairKinds k;
        for (const BtgPair& p : pairs) k.add(ref::pairKind(p, props.data(), view.view()));
        return k;
    }
};

// speculative: the soft step's narrowphase (two spheres collided afresh).
inline std::vector<BtgManifold> runDevice(cl::Context& ctx, const Fixture& f, const std::vector<BtgCachedContact>& cache,
                                          const std::vector<BtgPersistentManifold>& gjkCache,
                                          std::vector<BtgPersistentManifold>* states, bool speculative = false)
{
    DeviceWorld w(ctx);
    w.speculativeContacts = speculative;
    w.numBodies = int(f.pos.size());
    w.pos.upload(ctx, f.pos);
    w.rot.upload(ctx, f.rot);
    w.props.upload(ctx, f.props);
    f.view.upload(w);
    w.pairCapacity = f.pairs.size();
    w.pairs.upload(ctx, f.pairs);
    std::vector<uint> counters(kNumCounters, 0);
    counters[kPairCount] = uint(f.pairs.size());
    counters[kPrevContactCount] = uint(cache.size());
    w.counters.upload(ctx, counters);
    w.contactCapacity = std::max<size_t>(cache.size(), 1);
    std::vector<BtgCachedContact> c = cache;
    c.resize(w.contactCapacity, BtgCachedContact{});
    w.contactCache.upload(ctx, c);
    std::vector<BtgPersistentManifold> g = gjkCache;
    g.resize(w.contactCapacity, BtgPersistentManifold{});
    w.gjkCache.upload(ctx, g);
    w.gjkCacheCurrent = true;
    groupPairsByKind(w, f.kinds());
    narrowphase(w, f.kinds());
    if (w.gjkPairState.capacity() >= f.pairs.size()) *states = w.gjkPairState.download(ctx, f.pairs.size());
    else states->assign(f.pairs.size(), btgEmptyPersistent(0, 0, BTG_PAIR_NONE));  // none kept
    return w.manifolds.download(ctx, f.pairs.size());
}

inline void expectSame(const BtgManifold& dev, const BtgManifold& ref, size_t i)
{
    SCOPED_TRACE("pair " + std::to_string(i));
    ASSERT_EQ(dev.numPoints, ref.numPoints);
    for (int k = 0; k < ref.numPoints; ++k) {
        const BtgManifoldPoint &d = dev.points[k], &r = ref.points[k];
        EXPECT_EQ(d.featureId, r.featureId);
        EXPECT_NEAR(d.distance, r.distance, tol::kContactDepth);
        EXPECT_NEAR(d.px, r.px, tol::kContactPoint);
        EXPECT_NEAR(d.py, r.py, tol::kContactPoint);
        EXPECT_NEAR(d.pz, r.pz, tol::kContactPoint);
        EXPECT_GE(d.nx * r.nx + d.ny * r.ny + d.nz * r.nz, tol::kNormalDot);
    }
}

}  // namespace btgpu::test::gjk
