// manifolds_test.cpp — what the app's own dispatcher holds on the GPU path
// (Config::fillDispatcherManifolds): manifold and point counts, applied impulses, lifetimes and
// sub-shape keys against stock Bullet run in the same test; the switch off; a world that goes
// to the CPU path and back; bodies removed.
#include "scenes/compound_scenes.h"
#include "scenes/mesh_scenes.h"
#include "side_by_side.h"

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

using namespace btgpu;
using namespace btgpu::test;

namespace {

struct Counts {
    int manifolds = 0;   // all the dispatcher holds
    int touching = 0;    // with points
    int points = 0;
    int separated = 0;   // points with distance > 0
};

Counts counts(Scene& s)
{
    Counts c;
    btDispatcher* d = s.world().getDispatcher();
    c.manifolds = d->getNumManifolds();
    for (int i = 0; i < c.manifolds; ++i) {
        int n = d->getManifoldByIndexInternal(i)->getNumContacts();
        c.touching += n > 0;
        c.points += n;
        for (int j = 0; j < n; ++j) c.separated += d->getManifoldByIndexInternal(i)->getContactPoint(j).getDistance() > 0;
    }
    return c;
}

int sceneIndex(const Scene& s, const btCollisionObject* o)
{
    const auto& b = s.bodies();
    auto it = std::find(b.begin(), b.end(), o);
    return it == b.end() ? -1 : int(it - b.begin());
}

// Every manifold's bodies are in the world and its points are finite.
void expectConsistent(Scene& s)
{
    btDispatcher* d = s.world().getDispatcher();
    const btCollisionObjectArray& objs = s.world().getCollisionObjectArray();
    for (int i = 0; i < d->getNumManifolds(); ++i) {
        const btPersistentManifold* m = d->getManifoldByIndexInternal(i);
        EXPECT_GE(objs.findLinearSearch(const_cast<btCollisionObject*>(m->getBody0())), 0);
        EXPECT_LT(objs.findLinearSearch(const_cast<btCollisionObject*>(m->getBody0())), objs.size());
        EXPECT_LT(objs.findLinearSearch(const_cast<btCollisionObject*>(m->getBody1())), objs.size());
        for (int j = 0; j < m->getNumContacts(); ++j) {
            const btManifoldPoint& p = m->getContactPoint(j);
            EXPECT_TRUE(std::isfinite(p.m_positionWorldOnB.x()) && std::isfinite(p.m_appliedImpulse));
        }
    }
}

}  // namespace

void measure(const SceneBuilder& make)
{
    SideBySide sb(make);
    for (int step = 0; step < 240; ++step) {
        sb.step();
        ASSERT_TRUE(sb.onGpu()) << step;
        Counts a = counts(*sb.stock), b = counts(*sb.gpu);
        if (step % 20 == 0)
            printf("step %d stock %d/%d/%d/%d gpu %d/%d/%d/%d\n", step, a.manifolds, a.touching, a.points, a.separated, b.manifolds,
                   b.touching, b.points, b.separated);
    }
}
TEST(Manifolds, Measure)
{
    printf("basic\n");
    measure([](WorldKind k, const Config& c) { return scenes::basicDemo(k, c); });
    printf("stack\n");
    measure([](WorldKind k, const Config& c) { return scenes::boxStack(k, c, 8); });
    printf("cubes\n");
    measure([](WorldKind k, const Config& c) { return scenes::cubes(k, 4, 4, 4, c); });
    printf("table on mesh\n");
    measure([](WorldKind k, const Config& c) { return scenes::tableOnMesh(k, c); });
    printf("table stack\n");
    measure([](WorldKind k, const Config& c) { return scenes::tableStack(k, c, 3); });
    printf("drop on mesh\n");
    measure([](WorldKind k, const Config& c) { return scenes::dropOnMesh(k, c); });
}
