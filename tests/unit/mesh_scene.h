// mesh_scene.h — Bullet triangle meshes for the midphase and mesh narrowphase unit tests: a
// terrain-like grid in two parts (16- and 32-bit indices) or a hand-listed triangle list, read
// into the GPU mesh table by compat's MeshTables (the world's own reader), plus convex bodies
// over it, their pairs with the mesh and the uploads of a DeviceWorld.
#pragma once
#include "../compat/mesh_tables.h"
#include "reference/narrowphase.h"
#include "shape_tables.h"
#include "stages/find_pairs.h"
#include "world/device_world.h"

#include <btBulletDynamicsCommon.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

namespace btgpu::test {

// The app's data, kept alive as long as Bullet's shape points into it.
struct BulletMesh {
    std::vector<float> vertices0, vertices1;
    std::vector<unsigned short> indices0;  // part 0: PHY_SHORT, as BenchmarkDemo's landscape
    std::vector<int> indices1;             // part 1: PHY_INTEGER
    std::unique_ptr<btTriangleIndexVertexArray> array;
    std::unique_ptr<btBvhTriangleMeshShape> shape;

    static float height(float x, float z) { return 0.4f * std::sin(0.7f * x) * std::cos(0.5f * z); }

    // An n x n grid of quads of side `cell` from x0, z0 (two triangles each), heights by height().
    static void grid(int n, float cell, float x0, float z0, bool flat, std::vector<float>* v, std::vector<int>* idx)
    {
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) {
                float x = x0 + cell * float(i), z = z0 + cell * float(j);
                v->insert(v->end(), {x, flat ? 0.0f : height(x, z), z});
            }
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                int a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
                idx->insert(idx->end(), {a, b, d, a, d, c});
            }
    }

    // Two parts side by side: x in [-n cell, 0] (16-bit) and [0, n cell] (32-bit), z in [-n cell/2, n cell/2].
    static std::unique_ptr<BulletMesh> terrain(int n, float cell, bool flat)
    {
        auto m = std::make_unique<BulletMesh>();
        std::vector<int> i0;
        grid(n, cell, -float(n) * cell, -0.5f * float(n) * cell, flat, &m->vertices0, &i0);
        grid(n, cell, 0.0f, -0.5f * float(n) * cell, flat, &m->vertices1, &m->indices1);
        m->indices0.assign(i0.begin(), i0.end());
        m->build();
        return m;
    }

    void build()
    {
        array = std::make_unique<btTriangleIndexVertexArray>();
        btIndexedMesh p0;
        p0.m_numTriangles = int(indices0.size() / 3);
        p0.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(indices0.data());
        p0.m_triangleIndexStride = 3 * int(sizeof(unsigned short));
        p0.m_numVertices = int(vertices0.size() / 3);
        p0.m_vertexBase = reinterpret_cast<const unsigned char*>(vertices0.data());
        p0.m_vertexStride = 3 * int(sizeof(float));
        p0.m_indexType = PHY_SHORT;
        p0.m_vertexType = PHY_FLOAT;
        array->addIndexedMesh(p0, PHY_SHORT);
        if (!indices1.empty()) {
            btIndexedMesh p1 = p0;
            p1.m_numTriangles = int(indices1.size() / 3);
            p1.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(indices1.data());
            p1.m_triangleIndexStride = 3 * int(sizeof(int));
            p1.m_numVertices = int(vertices1.size() / 3);
            p1.m_vertexBase = reinterpret_cast<const unsigned char*>(vertices1.data());
            p1.m_indexType = PHY_INTEGER;
            array->addIndexedMesh(p1, PHY_INTEGER);
        }
        shape = std::make_unique<btBvhTriangleMeshShape>(array.get(), true);
    }
};

// Bodies over one mesh (row 0, static) and their pairs with it; the device world's columns.
struct MeshScene {
    ShapeTables t;  // convex shapes; the mesh row is appended by addMesh
    MeshTables meshes;
    std::vector<BtgFloat4> pos, rot;
    std::vector<BtgBodyProps> props;
    std::vector<BtgPair> pairs;
    std::vector<BtgHeightfield> heightfields;
    std::vector<float> heights;

    // The mesh shape row (BTG_SHAPE_MESH) of a Bullet mesh, `scaling` as a scaled wrapper's.
    int addMesh(const btBvhTriangleMeshShape* shape, float margin = 0.0f, BtgFloat4 scaling = btgMake4(1, 1, 1, 0))
    {
        std::string why;
        BtgShape s{};
        s.type = BTG_SHAPE_MESH;
        s.mesh = meshes.add(shape, &why);
        EXPECT_GE(s.mesh, 0) << why;
        s.param = scaling;
        s.margin = margin;
        s.breakingThreshold = 1e30f;  // a mesh's is huge; the convex's decides
        s.localAabbMin = btgMake4(-1e3f, -1e3f, -1e3f, 0);
        s.localAabbMax = btgMake4(1e3f, 1e3f, 1e3f, 0);
        t.shapes.push_back(s);
        return int(t.shapes.size()) - 1;
    }
    int body(int shape, BtgFloat4 p, BtgFloat4 q, uint flags)
    {
        BtgBodyProps bp{};
        bp.shape = shape;
        bp.flags = flags;
        pos.push_back(p);
        rot.push_back(q);
        props.push_back(bp);
        return int(pos.size()) - 1;
    }
    ref::MeshTablesView meshView() const
    {
        ref::MeshTablesView v;
        v.meshes = meshes.meshes.data();
        v.nodes = meshes.nodes.data();
        v.triangles = meshes.triangles.data();
        v.vertices = meshes.vertices.data();
        v.parts = meshes.parts.data();
        v.heightfields = heightfields.data();
        v.heights = heights.data();
        return v;
    }
    PairKinds kinds() const
    {
        PairKinds k;
        for (const BtgPair& p : pairs) {
            int kind = ref::pairKind(p, props.data(), t.view());
            if (kind != BTG_PAIR_NONE) k.add(kind);
        }
        return k;
    }
    // Pair slots in the device's kind-grouped order (stable by kind), mesh kinds only.
    std::vector<int> meshSlots() const
    {
        std::vector<int> slots;
        for (int kind = BTG_FIRST_MESH_PAIR_KIND; kind <= BTG_LAST_MESH_PAIR_KIND; ++kind)
            for (size_t i = 0; i < pairs.size(); ++i)
                if (ref::pairKind(pairs[i], props.data(), t.view()) == kind) slots.push_back(int(i));
        return slots;
    }
    template <class T>
    static void put(cl::Context& ctx, cl::DeviceArray<T>& a, std::vector<T> v)
    {
        if (v.empty()) v.resize(1);
        a.upload(ctx, v);
    }
    // Everything the midphase and the mesh narrowphase read, pairs counted and grouped by kind.
    void upload(DeviceWorld& w, size_t subPairCapacity) const
    {
        cl::Context& ctx = w.ctx;
        w.numBodies = int(pos.size());
        w.pos.upload(ctx, pos);
        w.rot.upload(ctx, rot);
        w.props.upload(ctx, props);
        t.upload(w);
        put(ctx, w.meshes, meshes.meshes);
        put(ctx, w.meshNodes, meshes.nodes);
        put(ctx, w.meshTriangles, meshes.triangles);
        put(ctx, w.meshVertices, meshes.vertices);
        put(ctx, w.meshParts, meshes.parts);
        put(ctx, w.heightfields, heightfields);
        put(ctx, w.heightfieldHeights, heights);
        w.pairCapacity = pairs.size() + 3;
        std::vector<BtgPair> padded = pairs;
        padded.resize(w.pairCapacity, BtgPair{0, 0});
        w.pairs.upload(ctx, padded);
        std::vector<uint> counters(kNumCounters, 0);
        counters[kPairCount] = uint(pairs.size());
        w.counters.upload(ctx, counters);
        w.subPairCapacity = subPairCapacity;
        w.manifolds.release();
        groupPairsByKind(w, kinds());
    }
};

}  // namespace btgpu::test
