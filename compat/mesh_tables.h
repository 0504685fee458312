// mesh_tables.h — the app's btBvhTriangleMeshShapes read into the GPU mesh table
// (kernels/shared/mesh.h): vertices and triangles through the shape's btStridingMeshInterface
// (every part; 8-, 16- and 32-bit indices; float or double vertices, as Bullet's node callback
// reads them), and the shape's own quantized BVH as it stands (nodes, escape indices,
// quantization). Each mesh is stored once, however many bodies or scaled wrappers use it. The
// app's objects are only read; a fingerprint of everything read tells when the app has edited
// its vertices or refitted its BVH (refitTree, partialRefitTree), and the mesh is then read again.
#pragma once
#include "shared/concave.h"

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

class btBvhTriangleMeshShape;
class btCollisionShape;
class btHeightfieldTerrainShape;

namespace btgpu {

struct MeshTables {
    std::vector<BtgMesh> meshes;
    std::vector<BtgBvhNode> nodes;
    std::vector<BtgTriangle> triangles;
    std::vector<BtgFloat4> vertices;
    std::vector<int> parts;
    std::vector<BtgHeightfield> heightfields;
    std::vector<float> heights;

    // The mesh row of `shape` (read the first time, and again when its fingerprint changed), or
    // -1 with *whyNot set when the GPU path cannot take it.
    int add(const btBvhTriangleMeshShape* shape, std::string* whyNot);
    // The heightfield row of `shape`, its heights read from the app's array now (heightfield_tables.cpp).
    int addHeightfield(const btHeightfieldTerrainShape* shape, std::string* whyNot);

private:
    struct Row {
        int row;
        std::uint64_t fingerprint;
    };
    std::unordered_map<const btBvhTriangleMeshShape*, Row> m_rowOf;
};

// The btBvhTriangleMeshShape under a mesh shape the GPU path may take (the shape itself, or a
// btScaledBvhTriangleMeshShape's child), else nullptr.
const btBvhTriangleMeshShape* bvhMeshOf(const btCollisionShape* shape);

// A hash of every byte the mesh table takes from the mesh (vertices, indices, the BVH's nodes
// and quantization, the interface's scaling); equal hashes: the table still holds.
std::uint64_t meshFingerprint(const btBvhTriangleMeshShape* shape);

// The fingerprints' hash of a buffer (in parallel chunks for megabytes).
std::uint64_t hashBytes(const void* data, size_t n);

// "" when the mesh can be simulated, else why not as bad input (a non-finite vertex, an index
// out of range). Reads every vertex: called when a mesh is first read.
std::string badMeshInput(const btBvhTriangleMeshShape* shape);

// The heightfield the GPU path may take (exactly btHeightfieldTerrainShape: a subclass may
// override getRawHeightFieldValue), else nullptr; its fingerprint (every height byte and every
// parameter the walk reads) and its bad input (a non-finite height, scaling or zero scaling).
const btHeightfieldTerrainShape* heightfieldOf(const btCollisionShape* shape);
std::uint64_t heightfieldFingerprint(const btHeightfieldTerrainShape* shape);
std::string badHeightfieldInput(const btHeightfieldTerrainShape* shape);

}  // namespace btgpu
