// shape_tables.h — Bullet collision shapes turned into the GPU shape table and hull tables.
// Boxes become 8-vertex hulls (margin inside the extents, as btBoxShape), convex hulls use
// Bullet's own face extraction run on a private copy (margin kept as an outward rounding; the
// app's shape is never changed), spheres and static planes are parameters. Anything else is
// refused with a reason (the world then runs on the CPU path). btBvhTriangleMeshShape and
// btScaledBvhTriangleMeshShape become mesh rows (mesh_tables.h). A shape of a known kind with
// unusable parameters gets a placeholder row and a reason: the bodies using it are kept out.
#pragma once
#include "mesh_tables.h"
#include "shared/types.h"

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

class btCollisionShape;
class btCompoundShape;
class btTransform;

namespace btgpu {

// A hull's faces, vertices and unique edges as Bullet's btConvexPolyhedron has them.
struct Polyhedron {
    std::vector<BtgFloat4> vertices, edges;
    std::vector<BtgFloat4> planes;
    std::vector<std::vector<int>> faces;
};

struct ShapeTables {
    std::vector<BtgShape> shapes;
    std::vector<BtgFloat4> vertices;
    std::vector<BtgFace> faces;
    std::vector<int> indices;
    std::vector<BtgFloat4> edges;
    std::vector<BtgChild> children;  // compound leaves (BtgShape::firstChild, numChildren)
    MeshTables meshTables;  // the meshes of BTG_SHAPE_MESH rows (BtgShape::mesh), each once
    std::unordered_map<const btCollisionShape*, int> rowOf;
    std::vector<std::string> badReason;             // per row: "" or why its bodies are kept out
    std::vector<const btCollisionShape*> shapeOf;   // per row
    std::vector<std::uint64_t> fingerprint;         // per row: shapeFingerprint when added
    std::vector<int> references;                    // per row: bodies using it at the last check

    // How each shape's contact breaking threshold is set (BtgShape::breakingThreshold), from
    // the dispatcher: with CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD (Bullet's default) the
    // shape's getContactBreakingThreshold(absolute), else `absolute` (gContactBreakingThreshold).
    bool relativeThreshold = true;
    float absoluteThreshold = 0.02f;

    // The shape's row (adding it the first time), or -1 with *whyNot set when the GPU path
    // cannot take it. Counts a reference to the row; the first reference of a check to a row
    // nothing referenced before is verified against the shape (its address may now hold
    // another shape, or the app changed it in place): a shape that changed gets a new row.
    int add(const btCollisionShape* shape, std::string* whyNot);
    // Starts a new count of references (the world then adds every body's shape). Rows nobody
    // references are never read again: the app may have deleted their shapes.
    void beginReferences();
    // True when the app changed a referenced shape in place since its row was built.
    bool changedSinceBuilt() const;
    // Rows added since the last call (the device tables need uploading).
    bool takeGrown();
    // Rows no body references (kept until the tables are cleared).
    size_t unreferenced() const;
    // Empties the tables; the hull faces of this build are kept for the next one only (so
    // hulls the app deleted meanwhile are forgotten after one build).
    void clear();

private:
    // A compound's row: its leaves, each a row of its own, appended to `children`. False with
    // *whyNot when a child is not served; *bad names a child that keeps the compound's bodies out.
    bool compoundRow(const btCompoundShape* compound, BtgShape& s, std::string* whyNot, std::string* bad);
    // The rows of one compound level into f, nested compounds recursed (parents are indices in
    // f.nodes until compoundRow places them); toBody carries this level's frame into the body's.
    struct Flattened {
        std::vector<BtgChild> leaves, nodes;
    };
    bool flatten(const btCompoundShape* compound, const btTransform& toBody, int parent, int depth,
                 const std::string& path, Flattened& f, std::string* whyNot, std::string* bad);
    struct CachedHull {
        std::uint64_t fingerprint;
        Polyhedron poly;
    };
    std::unordered_map<const btCollisionShape*, CachedHull> m_hullCache, m_previousHulls;
    std::vector<char> m_stale;  // per row: unreferenced at some check since it was verified
    bool m_grown = true;
};

// Radius of a sphere about the body origin that holds the shape (m); planes: 0.
float boundingRadius(const BtgShape& s);

}  // namespace btgpu
