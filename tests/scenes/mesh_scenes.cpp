// mesh_scenes.cpp — the mesh scenes: grid meshes read through btTriangleIndexVertexArray (the
// way BenchmarkDemo builds its landscape), with Bullet's quantized BVH.
#include "scenes/mesh_scenes.h"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>

#include <cmath>

namespace btgpu::scenes {

float landscapeHeight(float x, float z) { return 1.5f * std::sin(0.11f * x) * std::cos(0.07f * z) + 0.3f * std::sin(0.5f * x + 0.3f * z); }

namespace {

void grid(int n, float cell, float x0, float z0, bool flat, std::vector<float>* v, std::vector<int>* idx, int nx)
{
    for (int i = 0; i <= nx; ++i)
        for (int j = 0; j <= n; ++j) {
            float x = x0 + cell * float(i), z = z0 + cell * float(j);
            v->insert(v->end(), {x, flat ? 0.0f : landscapeHeight(x, z), z});
        }
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < n; ++j) {
            int a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
            idx->insert(idx->end(), {a, b, d, a, d, c});
        }
}

btIndexedMesh part(const std::vector<float>& v, const unsigned char* indices, int numTriangles, int indexSize,
                   PHY_ScalarType type)
{
    btIndexedMesh m;
    m.m_numTriangles = numTriangles;
    m.m_triangleIndexBase = indices;
    m.m_triangleIndexStride = 3 * indexSize;
    m.m_numVertices = int(v.size() / 3);
    m.m_vertexBase = reinterpret_cast<const unsigned char*>(v.data());
    m.m_vertexStride = 3 * int(sizeof(float));
    m.m_indexType = type;
    m.m_vertexType = PHY_FLOAT;
    return m;
}

}  // namespace

btBvhTriangleMeshShape* gridMesh(Scene& scene, int n, float cell, bool flat, bool twoParts, MeshData** out)
{
    MeshData* d = scene.ownData(new MeshData());
    const float half = 0.5f * float(n) * cell;
    const int n0 = twoParts ? n / 2 : n;
    std::vector<int> i0;
    grid(n, cell, -half, -half, flat, &d->vertices, &i0, n0);
    if (i0.size() / 3 <= 65535 * 3 && d->vertices.size() / 3 <= 65536) {
        d->shortIndices.assign(i0.begin(), i0.end());
    } else {
        d->intIndices = i0;  // too many vertices for 16 bits: one 32-bit part
    }
    if (twoParts) grid(n, cell, -half + float(n0) * cell, -half, flat, &d->vertices1, &d->intIndices, n - n0);
    auto* array = scene.ownData(new btTriangleIndexVertexArray());
    d->array = array;
    if (!d->shortIndices.empty())
        array->addIndexedMesh(part(d->vertices, reinterpret_cast<const unsigned char*>(d->shortIndices.data()),
                                   int(d->shortIndices.size() / 3), int(sizeof(unsigned short)), PHY_SHORT),
                              PHY_SHORT);
    if (twoParts || d->shortIndices.empty())
        array->addIndexedMesh(part(twoParts ? d->vertices1 : d->vertices,
                                   reinterpret_cast<const unsigned char*>(d->intIndices.data()),
                                   int(d->intIndices.size() / 3), int(sizeof(int)), PHY_INTEGER),
                              PHY_INTEGER);
    if (out) *out = d;
    return scene.ownShape(new btBvhTriangleMeshShape(array, true));
}

btHeightfieldTerrainShape* flatHeightfield(Scene& scene, int n, std::vector<float>** heights)
{
    auto* h = scene.ownData(new std::vector<float>(size_t(n) * size_t(n), 0.0f));
    if (heights) *heights = h;
    return scene.ownShape(new btHeightfieldTerrainShape(n, n, h->data(), 1, -1, 1, 1, PHY_FLOAT, false));
}

namespace {
void restBodies(Scene& scene)
{
    scene.addBody(scene.boxShape(btVector3(.5, .5, .5)), 1, btVector3(-2, btScalar(.6), btScalar(.3)));
    scene.addBody(scene.sphereShape(.5), 1, btVector3(2, btScalar(.6), btScalar(-.2)));
}
// A capsule and a cylinder on their sides, a cone upright and a box-like hull without polyhedral
// features, 0.1 m above y = 0 (bodies 1..4).
void convexRestBodies(Scene& scene)
{
    const btQuaternion side(btVector3(0, 0, 1), btScalar(SIMD_HALF_PI));
    const btQuaternion sideX(btVector3(1, 0, 0), btScalar(SIMD_HALF_PI));
    auto* capsule = scene.ownShape(new btCapsuleShape(btScalar(.3), btScalar(1.)));
    auto* cylinder = scene.ownShape(new btCylinderShape(btVector3(btScalar(.3), btScalar(.5), btScalar(.3))));
    auto* cone = scene.ownShape(new btConeShape(btScalar(.4), btScalar(1.)));
    scene.addBody(capsule, 1, btTransform(side, btVector3(btScalar(-3.2), btScalar(.4), btScalar(.3))));
    scene.addBody(cylinder, 1, btTransform(sideX, btVector3(btScalar(.3), btScalar(.4), btScalar(-.2))));
    scene.addBody(cone, 1, btTransform(btQuaternion::getIdentity(), btVector3(btScalar(3.3), btScalar(.6), btScalar(.4))));
    std::vector<btVector3> corners;  // a hull without polyhedral features: GJK on stock too
    for (int i = 0; i < 8; ++i)
        corners.emplace_back(i & 1 ? btScalar(.4) : btScalar(-.4), i & 2 ? btScalar(.3) : btScalar(-.3),
                             i & 4 ? btScalar(.4) : btScalar(-.4));
    scene.addBody(scene.hullShape(corners), 1, btVector3(btScalar(.6), btScalar(.45), btScalar(3.2)));
}
void dropBodies(Scene& scene)
{
    btCollisionShape* box = scene.boxShape(btVector3(btScalar(.3), btScalar(.3), btScalar(.3)));
    btCollisionShape* sphere = scene.sphereShape(btScalar(.3));
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) {
            const bool isBox = (i + j) % 2 == 0;
            scene.addBody(isBox ? box : sphere, 1, btVector3(btScalar(-6.75 + 1.5 * i), btScalar(1.3), btScalar(-6.75 + 1.5 * j)));
        }
}
}  // namespace

ScenePtr restOnHeightfield(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "rest_on_heightfield");
    scene->addBody(flatHeightfield(*scene, 17), 0, btVector3(0, 0, 0));
    restBodies(*scene);
    return scene;
}

ScenePtr convexRestOnHeightfield(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "convex_rest_on_heightfield");
    scene->addBody(flatHeightfield(*scene, 17), 0, btVector3(0, 0, 0));
    convexRestBodies(*scene);
    return scene;
}

ScenePtr convexRestOnMesh(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "convex_rest_on_mesh");
    scene->addBody(gridMesh(*scene, 16, 1.0f, true, true), 0, btVector3(0, 0, 0));
    convexRestBodies(*scene);
    return scene;
}

ScenePtr dropOnHeightfield(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "drop_on_heightfield");
    scene->addBody(flatHeightfield(*scene, 25), 0, btVector3(0, 0, 0));
    dropBodies(*scene);
    return scene;
}

ScenePtr restOnMesh(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "rest_on_mesh");
    scene->addBody(gridMesh(*scene, 16, 1.0f, true, true), 0, btVector3(0, 0, 0));
    scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, btVector3(-2, btScalar(.6), btScalar(.3)));
    scene->addBody(scene->sphereShape(.5), 1, btVector3(2, btScalar(.6), btScalar(-.2)));
    return scene;
}

ScenePtr dropOnMesh(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "drop_on_mesh");
    scene->addBody(gridMesh(*scene, 24, 1.0f, true, true), 0, btVector3(0, 0, 0));
    btCollisionShape* box = scene->boxShape(btVector3(btScalar(.3), btScalar(.3), btScalar(.3)));
    btCollisionShape* sphere = scene->sphereShape(btScalar(.3));
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) {
            const bool isBox = (i + j) % 2 == 0;
            scene->addBody(isBox ? box : sphere, 1,
                           btVector3(btScalar(-6.75 + 1.5 * i), btScalar(1.3), btScalar(-6.75 + 1.5 * j)));
        }
    return scene;
}

ScenePtr sharedMesh(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "shared_mesh");
    btBvhTriangleMeshShape* mesh = gridMesh(*scene, 8, 1.0f, true, false);
    scene->addBody(mesh, 0, btVector3(-10, 0, 0));
    scene->addBody(mesh, 0, btVector3(10, 0, 0));
    for (int side = -1; side <= 1; side += 2) {
        scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, btVector3(btScalar(10 * side - 1.3), btScalar(.7), 0));
        scene->addBody(scene->sphereShape(.5), 1, btVector3(btScalar(10 * side + 1.7), btScalar(.7), btScalar(.4)));
    }
    return scene;
}

ScenePtr landscape(WorldKind kind, const Config& config, int count, int quads)
{
    auto scene = std::make_unique<Scene>(kind, config, "landscape");
    scene->addBody(gridMesh(*scene, quads, 200.0f / float(quads), false, false), 0, btVector3(0, 0, 0));
    btCollisionShape* box = scene->boxShape(btVector3(btScalar(.5), btScalar(.5), btScalar(.5)));
    btCollisionShape* sphere = scene->sphereShape(btScalar(.5));
    btConvexHullShape* hull = scene->hullShape({{-.5, -.4, -.5}, {.5, -.4, -.5}, {.5, -.4, .5}, {-.5, -.4, .5},
                                                {-.3, .4, -.3}, {.3, .4, -.3}, {.3, .4, .3}, {-.3, .4, .3}});
    // With polyhedral features: the GPU path has triangle routines for spheres, boxes and such
    // hulls; a hull without them (a GJK row) against triangles still falls back.
    hull->initializePolyhedralFeatures();
    const int side = std::max(1, int(std::ceil(std::sqrt(double(count) / 4.0))));
    int made = 0;
    for (int layer = 0; made < count; ++layer)
        for (int i = 0; i < side && made < count; ++i)
            for (int j = 0; j < side && made < count; ++j, ++made) {
                float x = -0.5f * 1.6f * float(side) + 1.6f * float(i), z = -0.5f * 1.6f * float(side) + 1.6f * float(j);
                btCollisionShape* s = made % 3 == 0 ? box : made % 3 == 1 ? sphere : hull;
                scene->addBody(s, 1, btVector3(x, landscapeHeight(x, z) + 3.0f + 1.6f * float(layer), z));
            }
    return scene;
}

}  // namespace btgpu::scenes
