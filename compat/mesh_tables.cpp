// mesh_tables.cpp — reading btBvhTriangleMeshShape (and btScaledBvhTriangleMeshShape's child)
// into the mesh table: the mesh interface part by part, the quantized BVH node by node. What
// Bullet's own traversal would not give the same answer for is refused with a reason.
#include "mesh_tables.h"

#include "parallel_rows.h"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <typeinfo>

namespace btgpu {

namespace {

// Protected members of btQuantizedBvh Bullet offers no getter for, read through pointers to
// member taken inside a derived class (nothing is ever constructed).
struct BvhPeek : btQuantizedBvh {
    static constexpr btVector3 btQuantizedBvh::*kAabbMin = &BvhPeek::m_bvhAabbMin;
    static constexpr btVector3 btQuantizedBvh::*kAabbMax = &BvhPeek::m_bvhAabbMax;
    static constexpr btVector3 btQuantizedBvh::*kQuantization = &BvhPeek::m_bvhQuantization;
    static constexpr int btQuantizedBvh::*kCurNodeIndex = &BvhPeek::m_curNodeIndex;
};

// One part of a mesh interface, locked for reading and unlocked when done.
struct LockedPart {
    const btStridingMeshInterface* mesh;
    int part;
    const unsigned char* vertexBase = nullptr;
    const unsigned char* indexBase = nullptr;
    int numVerts = 0, stride = 0, indexStride = 0, numFaces = 0;
    PHY_ScalarType type = PHY_FLOAT, indexType = PHY_INTEGER;
    LockedPart(const btStridingMeshInterface* m, int p) : mesh(m), part(p)
    {
        mesh->getLockedReadOnlyVertexIndexBase(&vertexBase, numVerts, type, stride, &indexBase, indexStride, numFaces,
                                               indexType, part);
    }
    ~LockedPart() { mesh->unLockReadOnlyVertexBase(part); }
    int index(int face, int j) const
    {
        const unsigned char* p = indexBase + size_t(face) * size_t(indexStride);
        if (indexType == PHY_SHORT) return reinterpret_cast<const unsigned short*>(p)[j];
        if (indexType == PHY_INTEGER) return int(reinterpret_cast<const unsigned int*>(p)[j]);
        return reinterpret_cast<const unsigned char*>(p)[j];
    }
    // As MyNodeOverlapCallback::processNode: the interface's scaling times each coordinate.
    btVector3 vertex(int i, const btVector3& scaling) const
    {
        const unsigned char* p = vertexBase + size_t(i) * size_t(stride);
        if (type == PHY_FLOAT) {
            const float* f = reinterpret_cast<const float*>(p);
            return btVector3(f[0] * scaling.getX(), f[1] * scaling.getY(), f[2] * scaling.getZ());
        }
        const double* d = reinterpret_cast<const double*>(p);
        return btVector3(btScalar(d[0]) * scaling.getX(), btScalar(d[1]) * scaling.getY(),
                         btScalar(d[2]) * scaling.getZ());
    }
};

// Hashes a buffer 32 bytes at a time in four independent lanes (a fingerprint of millions of
// vertices each step must be cheap); buffers of megabytes are split into chunks hashed on the
// host's cores and combined in order.
std::uint64_t hashRange(const unsigned char* c, size_t n)
{
    std::uint64_t h[4] = {0x9e3779b97f4a7c15ull, 0xc2b2ae3d27d4eb4full, 0x165667b19e3779f9ull, 0x27d4eb2f165667c5ull};
    size_t i = 0;
    for (; i + 32 <= n; i += 32)
        for (int k = 0; k < 4; ++k) {
            std::uint64_t w;
            std::memcpy(&w, c + i + 8 * size_t(k), 8);
            h[k] = (h[k] ^ w) * 0x100000001b3ull;
            h[k] ^= h[k] >> 29;
        }
    std::uint64_t x = h[0] ^ (h[1] * 31) ^ (h[2] * 961) ^ (h[3] * 29791);
    for (; i < n; ++i) x = (x ^ c[i]) * 0x100000001b3ull;
    return x ^ n;
}

struct Hasher {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    void combine(std::uint64_t v)
    {
        h = (h ^ v) * 0x100000001b3ull;
        h ^= h >> 31;
    }
    void bytes(const void* data, size_t n)
    {
        const unsigned char* c = static_cast<const unsigned char*>(data);
        const size_t chunk = size_t(1) << 20;
        if (n < 2 * chunk) {
            combine(hashRange(c, n));
            return;
        }
        const size_t pieces = (n + chunk - 1) / chunk;
        std::vector<std::uint64_t> part(pieces);
        forEachChunk(pieces, 1, [&](size_t begin, size_t end, int) {
            for (size_t p = begin; p < end; ++p) part[p] = hashRange(c + p * chunk, std::min(chunk, n - p * chunk));
        });
        for (std::uint64_t v : part) combine(v);
    }
    template <class T>
    void value(const T& v)
    {
        bytes(&v, sizeof(v));
    }
    void vec(const btVector3& v)
    {
        float f[3] = {v.x(), v.y(), v.z()};
        bytes(f, sizeof(f));
    }
};

btOptimizedBvh* bvhOf(const btBvhTriangleMeshShape* shape)
{
    // getOptimizedBvh is not const in Bullet; it only returns the pointer.
    return const_cast<btBvhTriangleMeshShape*>(shape)->getOptimizedBvh();
}

std::string unservedReason(const btBvhTriangleMeshShape* shape)
{
    btOptimizedBvh* bvh = bvhOf(shape);
    if (!bvh) return "btBvhTriangleMeshShape without a BVH (built with buildBvh = false)";
    if (!bvh->isQuantized()) return "btBvhTriangleMeshShape without quantized AABB compression";
    const btStridingMeshInterface* mesh = shape->getMeshInterface();
    if (!mesh) return "btBvhTriangleMeshShape without a mesh interface";
    if (mesh->getNumSubParts() > (1 << (31 - BTG_BVH_PART_SHIFT)))
        return "triangle mesh with more parts than Bullet's BVH can number";
    for (int p = 0; p < mesh->getNumSubParts(); ++p) {
        LockedPart part(mesh, p);
        if (part.type != PHY_FLOAT && part.type != PHY_DOUBLE) return "triangle mesh vertices neither float nor double";
        if (part.indexType != PHY_INTEGER && part.indexType != PHY_SHORT && part.indexType != PHY_UCHAR)
            return "triangle mesh indices neither 8, 16 nor 32 bit";
    }
    return "";
}

}  // namespace

std::uint64_t hashBytes(const void* data, size_t n)
{
    Hasher h;
    h.bytes(data, n);
    return h.h;
}

const btBvhTriangleMeshShape* bvhMeshOf(const btCollisionShape* shape)
{
    if (shape->getShapeType() == TRIANGLE_MESH_SHAPE_PROXYTYPE && typeid(*shape) == typeid(btBvhTriangleMeshShape))
        return static_cast<const btBvhTriangleMeshShape*>(shape);
    if (shape->getShapeType() == SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE &&
        typeid(*shape) == typeid(btScaledBvhTriangleMeshShape)) {
        const btBvhTriangleMeshShape* child = static_cast<const btScaledBvhTriangleMeshShape*>(shape)->getChildShape();
        if (child && typeid(*child) == typeid(btBvhTriangleMeshShape)) return child;
    }
    return nullptr;
}

std::uint64_t meshFingerprint(const btBvhTriangleMeshShape* shape)
{
    Hasher h;
    const btStridingMeshInterface* mesh = shape->getMeshInterface();
    btOptimizedBvh* bvh = bvhOf(shape);
    h.value(reinterpret_cast<std::uintptr_t>(mesh));
    h.value(reinterpret_cast<std::uintptr_t>(bvh));
    if (mesh) {
        h.vec(mesh->getScaling());
        const int parts = mesh->getNumSubParts();
        h.value(parts);
        for (int p = 0; p < parts; ++p) {
            LockedPart part(mesh, p);
            int header[6] = {part.numVerts, part.stride, part.indexStride, part.numFaces, int(part.type),
                             int(part.indexType)};
            h.bytes(header, sizeof(header));
            if (part.vertexBase && part.numVerts > 0) h.bytes(part.vertexBase, size_t(part.numVerts) * size_t(part.stride));
            if (part.indexBase && part.numFaces > 0)
                h.bytes(part.indexBase, size_t(part.numFaces) * size_t(part.indexStride));
        }
    }
    if (bvh && bvh->isQuantized()) {
        h.vec(bvh->*BvhPeek::kAabbMin);
        h.vec(bvh->*BvhPeek::kAabbMax);
        h.vec(bvh->*BvhPeek::kQuantization);
        const int n = bvh->*BvhPeek::kCurNodeIndex;
        h.value(n);
        const QuantizedNodeArray& nodes = bvh->getQuantizedNodeArray();
        if (n > 0 && nodes.size() >= n) h.bytes(&nodes[0], size_t(n) * sizeof(btQuantizedBvhNode));
    }
    return h.h;
}

std::string badMeshInput(const btBvhTriangleMeshShape* shape)
{
    const btStridingMeshInterface* mesh = shape->getMeshInterface();
    if (!mesh || !bvhOf(shape) || !unservedReason(shape).empty()) return "";  // refused elsewhere, with its reason
    const btVector3& scaling = mesh->getScaling();
    if (!std::isfinite(scaling.x()) || !std::isfinite(scaling.y()) || !std::isfinite(scaling.z()))
        return "non-finite mesh interface scaling";
    for (int p = 0; p < mesh->getNumSubParts(); ++p) {
        LockedPart part(mesh, p);
        for (int i = 0; i < part.numVerts; ++i) {
            btVector3 v = part.vertex(i, scaling);
            if (!std::isfinite(v.x()) || !std::isfinite(v.y()) || !std::isfinite(v.z()))
                return "non-finite mesh vertex " + std::to_string(i) + " of part " + std::to_string(p);
        }
        for (int f = 0; f < part.numFaces; ++f)
            for (int j = 0; j < 3; ++j) {
                int k = part.index(f, j);
                if (k < 0 || k >= part.numVerts)
                    return "mesh triangle " + std::to_string(f) + " of part " + std::to_string(p) +
                           " indexes a vertex out of range";
            }
    }
    return "";
}

int MeshTables::add(const btBvhTriangleMeshShape* shape, std::string* whyNot)
{
    const std::uint64_t print = meshFingerprint(shape);
    auto it = m_rowOf.find(shape);
    if (it != m_rowOf.end() && it->second.fingerprint == print) return it->second.row;
    std::string why = unservedReason(shape);
    if (!why.empty()) {
        *whyNot = why;
        return -1;
    }
    const btStridingMeshInterface* mesh = shape->getMeshInterface();
    btOptimizedBvh* bvh = bvhOf(shape);
    BtgMesh m{};
    const btVector3 lo = bvh->*BvhPeek::kAabbMin, hi = bvh->*BvhPeek::kAabbMax, q = bvh->*BvhPeek::kQuantization;
    m.bvhMin = btgMake4(lo.x(), lo.y(), lo.z(), 0.0f);
    m.bvhMax = btgMake4(hi.x(), hi.y(), hi.z(), 0.0f);
    m.bvhQuantization = btgMake4(q.x(), q.y(), q.z(), 0.0f);
    // The walk's end is Bullet's m_curNodeIndex (the node array has one spare node).
    const int numNodes = bvh->*BvhPeek::kCurNodeIndex;
    const QuantizedNodeArray& nodes = bvh->getQuantizedNodeArray();
    if (numNodes < 0 || numNodes > nodes.size()) {
        *whyNot = "btBvhTriangleMeshShape's BVH has fewer nodes than it claims";
        return -1;
    }
    m.firstNode = int(this->nodes.size());
    m.numNodes = numNodes;
    for (int i = 0; i < numNodes; ++i) {
        const btQuantizedBvhNode& n = nodes[i];
        BtgBvhNode d;
        d.minXY = uint(n.m_quantizedAabbMin[0]) | uint(n.m_quantizedAabbMin[1]) << 16;
        d.minZMaxX = uint(n.m_quantizedAabbMin[2]) | uint(n.m_quantizedAabbMax[0]) << 16;
        d.maxYZ = uint(n.m_quantizedAabbMax[1]) | uint(n.m_quantizedAabbMax[2]) << 16;
        d.escapeOrTriangle = n.m_escapeIndexOrTriangleIndex;
        this->nodes.push_back(d);
    }
    m.firstTriangle = int(triangles.size());
    m.firstPart = int(parts.size());
    m.numParts = mesh->getNumSubParts();
    const btVector3& scaling = mesh->getScaling();
    int first = 0;
    for (int p = 0; p < m.numParts; ++p) {
        LockedPart part(mesh, p);
        parts.push_back(first);
        const int base = int(vertices.size());
        for (int i = 0; i < part.numVerts; ++i) {
            btVector3 v = part.vertex(i, scaling);
            vertices.push_back(btgMake4(v.x(), v.y(), v.z(), 0.0f));
        }
        for (int f = 0; f < part.numFaces; ++f) {
            BtgTriangle t{base + part.index(f, 0), base + part.index(f, 1), base + part.index(f, 2), 0};
            triangles.push_back(t);
        }
        first += part.numFaces;
    }
    m.numTriangles = first;
    // A leaf names (part, triangle): both must exist, or the walk would read past the tables.
    for (int i = 0; i < numNodes; ++i) {
        int x = nodes[i].m_escapeIndexOrTriangleIndex;
        if (x < 0) {
            if (i - x > numNodes) {
                *whyNot = "btBvhTriangleMeshShape's BVH escapes past its end";
                return -1;
            }
            continue;
        }
        int part = x >> BTG_BVH_PART_SHIFT, index = x & BTG_BVH_TRIANGLE_MASK;
        int inPart = part + 1 < m.numParts ? parts[size_t(m.firstPart + part + 1)] - parts[size_t(m.firstPart + part)]
                                           : first - (part < m.numParts ? parts[size_t(m.firstPart + part)] : 0);
        if (part >= m.numParts || index >= inPart) {
            *whyNot = "btBvhTriangleMeshShape's BVH names a triangle its mesh does not have (BVH not rebuilt after "
                      "the mesh changed)";
            return -1;
        }
    }
    const int row = int(meshes.size());
    meshes.push_back(m);
    m_rowOf[shape] = Row{row, print};
    return row;
}

}  // namespace btgpu
