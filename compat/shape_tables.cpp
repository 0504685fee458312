// shape_tables.cpp — conversion of btBoxShape, btConvexHullShape and btConvexPointCloudShape,
// btSphereShape, btStaticPlaneShape and the BVH triangle meshes and heightfields into the GPU
// tables, and of the support-function convex shapes through convex_rows, reading the app's
// shapes only.
#include "shape_tables.h"

#include "convex_rows.h"
#include "parallel_rows.h"
#include "shape_checks.h"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/BroadphaseCollision/btDbvt.h>
#include <BulletCollision/CollisionShapes/btConvexPolyhedron.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <typeinfo>

namespace btgpu {

namespace {

BtgFloat4 f4(const btVector3& v, float w = 0.0f) { return btgMake4(v.x(), v.y(), v.z(), w); }

void setLocalAabb(BtgShape& s, const btCollisionShape* shape)
{
    btVector3 mn, mx;
    btTransform id;
    id.setIdentity();
    shape->getAabb(id, mn, mx);
    s.localAabbMin = f4(mn);
    s.localAabbMax = f4(mx);
}

// Bullet's face extraction (btConvexHullComputer, coplanar triangles merged) as the app's
// shape would get it from initializePolyhedralFeatures, run on a private copy: the app's
// shape is never changed (a shape left with polyhedral features takes other code paths in
// Bullet, so a world falling back would no longer equal stock). Features the app computed
// itself are read as they are.
bool computePolyhedron(const btCollisionShape* shape, Polyhedron* out, std::string* whyNot)
{
    const btConvexPolyhedron* poly = static_cast<const btPolyhedralConvexShape*>(shape)->getConvexPolyhedron();
    std::unique_ptr<btConvexHullShape> copy;
    if (!poly) {
        int n = 0;
        const btVector3* points = hullPoints(shape, &n);
        copy = std::make_unique<btConvexHullShape>(&points[0].x(), n, int(sizeof(btVector3)));
        copy->setLocalScaling(shape->getLocalScaling());
        copy->setMargin(shape->getMargin());
        if (!copy->initializePolyhedralFeatures() || !copy->getConvexPolyhedron()) {
            *whyNot = "convex hull without polyhedral features";
            return false;
        }
        poly = copy->getConvexPolyhedron();
    }
    if (poly->m_vertices.size() < 4 || poly->m_faces.size() < 4) {
        *whyNot = "degenerate convex hull (" + std::to_string(poly->m_vertices.size()) + " vertices, " +
                  std::to_string(poly->m_faces.size()) + " faces)";
        return false;
    }
    for (int i = 0; i < poly->m_vertices.size(); ++i) out->vertices.push_back(f4(poly->m_vertices[i]));
    for (int i = 0; i < poly->m_faces.size(); ++i) {
        const btFace& f = poly->m_faces[i];
        if (f.m_indices.size() < 3) {
            *whyNot = "convex hull face with fewer than 3 vertices";
            return false;
        }
        out->planes.push_back(btgMake4(f.m_plane[0], f.m_plane[1], f.m_plane[2], f.m_plane[3]));
        std::vector<int> loop(size_t(f.m_indices.size()));
        for (int k = 0; k < f.m_indices.size(); ++k) loop[size_t(k)] = f.m_indices[k];
        out->faces.push_back(std::move(loop));
    }
    for (int i = 0; i < poly->m_uniqueEdges.size(); ++i) out->edges.push_back(f4(poly->m_uniqueEdges[i].normalized()));
    return true;
}

void appendPolyhedron(ShapeTables& t, BtgShape& s, const Polyhedron& poly)
{
    s.firstVertex = int(t.vertices.size());
    s.numVertices = int(poly.vertices.size());
    t.vertices.insert(t.vertices.end(), poly.vertices.begin(), poly.vertices.end());
    s.firstFace = int(t.faces.size());
    s.numFaces = int(poly.faces.size());
    for (size_t i = 0; i < poly.faces.size(); ++i) {
        BtgFace face{};
        face.plane = poly.planes[i];
        face.firstIndex = int(t.indices.size());
        face.numIndices = int(poly.faces[i].size());
        t.indices.insert(t.indices.end(), poly.faces[i].begin(), poly.faces[i].end());
        t.faces.push_back(face);
    }
    s.firstEdge = int(t.edges.size());
    s.numEdges = int(poly.edges.size());
    t.edges.insert(t.edges.end(), poly.edges.begin(), poly.edges.end());
}

void appendBox(ShapeTables& t, BtgShape& s, const btVector3& h)
{
    s.firstVertex = int(t.vertices.size());
    s.numVertices = 8;
    for (int i = 0; i < 8; ++i)
        t.vertices.push_back(btgMake4((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z(), 0.0f));
    // Faces as vertex loops counter-clockwise seen from outside (bit i of a vertex number is
    // the sign of axis i).
    static const int loops[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
    static const float normals[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const float ext[3] = {h.x(), h.y(), h.z()};
    s.firstFace = int(t.faces.size());
    s.numFaces = 6;
    for (int f = 0; f < 6; ++f) {
        BtgFace face{};
        int axis = f / 2;
        face.plane = btgMake4(normals[f][0], normals[f][1], normals[f][2], -ext[axis]);
        face.firstIndex = int(t.indices.size());
        face.numIndices = 4;
        for (int k = 0; k < 4; ++k) t.indices.push_back(loops[f][k]);
        t.faces.push_back(face);
    }
    s.firstEdge = int(t.edges.size());
    s.numEdges = 3;
    t.edges.push_back(btgMake4(1, 0, 0, 0));
    t.edges.push_back(btgMake4(0, 1, 0, 0));
    t.edges.push_back(btgMake4(0, 0, 1, 0));
}

}  // namespace

bool ShapeTables::compoundRow(const btCompoundShape* compound, BtgShape& s, std::string* whyNot, std::string* bad)
{
    s.type = BTG_SHAPE_COMPOUND;
    s.margin = compound->getMargin();
    setLocalAabb(s, compound);  // btCompoundShape::getAabb: its local box plus its margin, turned
    Flattened f;
    if (!flatten(compound, btTransform::getIdentity(), -1, 0, "", f, whyNot, bad)) return false;
    // Leaves first (the shape's range), then the nested compounds they name as parents.
    const int base = int(children.size()), firstNode = base + int(f.leaves.size());
    const bool nested = !f.nodes.empty();
    for (size_t k = 0; k < f.leaves.size(); ++k) {
        BtgChild& c = f.leaves[k];
        if (c.parent >= 0) c.parent += firstNode;
        // Bullet's child index names the leaf's manifolds; with nested compounds that index is
        // not unique within the body, so the leaf's place among the body's leaves does.
        if (nested) c.index = int(k);
    }
    for (BtgChild& c : f.nodes)
        if (c.parent >= 0) c.parent += firstNode;
    s.firstChild = base;
    s.numChildren = int(f.leaves.size());
    children.insert(children.end(), f.leaves.begin(), f.leaves.end());
    children.insert(children.end(), f.nodes.begin(), f.nodes.end());
    return true;
}

bool ShapeTables::flatten(const btCompoundShape* compound, const btTransform& toBody, int parent, int depth,
                          const std::string& path, Flattened& f, std::string* whyNot, std::string* bad)
{
    const bool tree = compound->getDynamicAabbTree() != nullptr;
    for (int i = 0; i < compound->getNumChildShapes(); ++i) {
        const btCollisionShape* child = compound->getChildShape(i);
        const std::string which = "compound child " + path + std::to_string(i) + " ";
        const btTransform& t = compound->getChildTransform(i);
        const btQuaternion q = t.getRotation();
        if (bad->empty() && !(std::isfinite(t.getOrigin().length2()) && std::isfinite(q.length2())))
            *bad = which + "has a non-finite transform";
        const btTransform composed = toBody * t;
        const btQuaternion cq = composed.getRotation();
        BtgChild c{};
        c.pos = f4(composed.getOrigin());
        c.rot = btgMake4(cq.x(), cq.y(), cq.z(), cq.w());
        c.index = i;
        c.parent = parent;
        c.useTree = tree ? 1 : 0;
        // The child as its holder's tree holds it (the box updateChildTransform or addChildShape left).
        const btDbvtNode* node = const_cast<btCompoundShape*>(compound)->getChildList()[i].m_node;
        if (node) {
            c.treeAabbMin = f4(node->volume.Mins());
            c.treeAabbMax = f4(node->volume.Maxs());
        } else {
            c.useTree = 0;
        }
        if (child->isCompound() && (depth >= 7 || typeid(*child) != typeid(btCompoundShape))) {
            *whyNot = which + "is a compound nested more than 8 deep or a subclass of btCompoundShape";
            return false;
        }
        // The body flag that keeps an empty shape out of every pair is a body's, not a child's.
        if (child->getShapeType() == EMPTY_SHAPE_PROXYTYPE) {
            *whyNot = which + "is a btEmptyShape";
            return false;
        }
        // A nested compound is a node with a row of its own (its box for the level's tests).
        const int row = add(child, whyNot);
        if (row < 0) {
            *whyNot = which + "(" + child->getName() + "): " + *whyNot;
            return false;
        }
        c.shape = row;
        if (child->isCompound()) {
            const int self = int(f.nodes.size());
            f.nodes.push_back(c);
            if (!flatten(static_cast<const btCompoundShape*>(child), composed, self, depth + 1,
                         path + std::to_string(i) + ".", f, whyNot, bad))
                return false;
            continue;
        }
        const int kind = shapes[size_t(row)].type;
        if (kind == BTG_SHAPE_PLANE || kind == BTG_SHAPE_MESH || kind == BTG_SHAPE_HEIGHTFIELD) {
            *whyNot = which + "is a " + child->getName() + " (concave or plane children are not on the GPU path yet)";
            return false;
        }
        if (bad->empty() && !badReason[size_t(row)].empty()) *bad = which + badReason[size_t(row)];
        f.leaves.push_back(c);
    }
    return true;
}

int ShapeTables::add(const btCollisionShape* shape, std::string* whyNot)
{
    auto it = rowOf.find(shape);
    if (it != rowOf.end()) {
        const size_t row = size_t(it->second);
        // Not referenced until now in this check: verified before it is taken again (it may be
        // another shape at a reused address, or changed in place).
        if (references[row] > 0 || (!m_stale[row] && shapeFingerprint(shape) == fingerprint[row])) {
            ++references[row];
            // A compound's leaves are in use as long as it is (their rows stay verified).
            const BtgShape& s = shapes[row];
            for (int k = 0; k < s.numChildren && s.type == BTG_SHAPE_COMPOUND; ++k)
                ++references[size_t(children[size_t(s.firstChild + k)].shape)];
            return it->second;
        }
        rowOf.erase(it);  // the old row stays, unreferenced; a new one is built below
    }
    BtgShape s{};
    s.firstVertex = s.firstFace = s.firstEdge = 0;
    const int type = shape->getShapeType();
    const btBvhTriangleMeshShape* mesh = bvhMeshOf(shape);
    const btHeightfieldTerrainShape* heightfield = heightfieldOf(shape);
    const bool known = type == BOX_SHAPE_PROXYTYPE || type == SPHERE_SHAPE_PROXYTYPE || type == STATIC_PLANE_PROXYTYPE ||
                       type == CONVEX_HULL_SHAPE_PROXYTYPE || type == CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE ||
                       isSupportShapeType(type) || mesh || heightfield || type == EMPTY_SHAPE_PROXYTYPE ||
                       (type == COMPOUND_SHAPE_PROXYTYPE && typeid(*shape) == typeid(btCompoundShape));
    s.mesh = -1;
    if (!known) {
        *whyNot = std::string("unsupported shape '") + shape->getName() + "'";
        return -1;
    }
    const std::uint64_t print = shapeFingerprint(shape);
    std::string bad = badShapeInput(shape);
    if (!bad.empty()) {
        // A placeholder that takes part in nothing: its bodies are excluded.
        s.type = BTG_SHAPE_SPHERE;
    } else if (type == BOX_SHAPE_PROXYTYPE) {
        auto* box = static_cast<const btBoxShape*>(shape);
        // A box the app gave polyhedral features meets other featured shapes by clipping on
        // stock, as a featured hull does (a world that also holds boxes without features, whose
        // box-box pairs stock still clips, falls back: cpu_path_rules.cpp).
        s.type = box->getConvexPolyhedron() ? BTG_SHAPE_HULL : BTG_SHAPE_BOX;
        s.margin = 0.0f;  // Bullet keeps a box's margin inside its extents
        appendBox(*this, s, box->getHalfExtentsWithMargin());
        // GJK against a box runs on the box shrunk by its margin, then rounded by it (support.h)
        s.convexType = BTG_CONVEX_BOX;
        s.param = f4(box->getHalfExtentsWithMargin(), box->getMargin());
        setLocalAabb(s, shape);
    } else if (type == SPHERE_SHAPE_PROXYTYPE) {
        auto* sphere = static_cast<const btSphereShape*>(shape);
        s.type = BTG_SHAPE_SPHERE;
        s.param = btgMake4(sphere->getRadius(), 0, 0, 0);
        s.margin = 0.0f;
        s.convexFlags = BTG_CONVEX_FLAG_SPHERE;  // Bullet's capsule-sphere closed form takes btSphereShape
        setLocalAabb(s, shape);
    } else if (type == EMPTY_SHAPE_PROXYTYPE) {
        // btEmptyShape collides with nothing (its bodies are BTG_BODY_NO_SHAPE); its AABB, the
        // origin grown by its margin, is a sphere row's of that radius.
        s.type = BTG_SHAPE_SPHERE;
        s.param = btgMake4(shape->getMargin(), 0, 0, 0);
        s.margin = 0.0f;
        setLocalAabb(s, shape);
    } else if (type == STATIC_PLANE_PROXYTYPE) {
        auto* plane = static_cast<const btStaticPlaneShape*>(shape);
        s.type = BTG_SHAPE_PLANE;
        s.param = f4(plane->getPlaneNormal().normalized(), plane->getPlaneConstant());
        s.localAabbMin = btgMake4(-1e30f, -1e30f, -1e30f, 0);
        s.localAabbMax = btgMake4(1e30f, 1e30f, 1e30f, 0);
    } else if (isSupportShapeType(type) || isFeaturelessHull(shape)) {
        if (!convexRow(shape, 1.0f, s, vertices, whyNot)) return -1;
        setLocalAabb(s, shape);
    } else if (mesh) {
        s.mesh = meshTables.add(mesh, whyNot);
        if (s.mesh < 0) return -1;
        s.type = BTG_SHAPE_MESH;
        // Bullet's collisionMarginTriangle: the body's concave shape's own margin.
        s.margin = shape->getMargin();
        // A btBvhTriangleMeshShape keeps its scaling in the mesh interface (read with the
        // vertices); a scaled wrapper scales the shared mesh's triangles itself.
        const btVector3 scaling = type == SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE ? shape->getLocalScaling()
                                                                               : btVector3(1, 1, 1);
        s.param = f4(scaling);
        setLocalAabb(s, shape);
    } else if (type == COMPOUND_SHAPE_PROXYTYPE) {
        std::string childBad;
        if (!compoundRow(static_cast<const btCompoundShape*>(shape), s, whyNot, &childBad)) return -1;
        if (bad.empty()) bad = childBad;
    } else if (heightfield) {
        // The heights are copied now; a change to the app's array changes the fingerprint and
        // the shape gets a new row, read again.
        s.mesh = meshTables.addHeightfield(heightfield, whyNot);
        if (s.mesh < 0) return -1;
        s.type = BTG_SHAPE_HEIGHTFIELD;
        s.margin = shape->getMargin();
        s.param = btgMake4(1, 1, 1, 0);  // the walk applies the heightfield's own scaling
        setLocalAabb(s, shape);
    } else {
        auto cached = m_hullCache.find(shape);
        if (cached == m_hullCache.end()) {
            auto previous = m_previousHulls.find(shape);
            if (previous != m_previousHulls.end())
                cached = m_hullCache.insert_or_assign(shape, std::move(previous->second)).first;
        }
        if (cached == m_hullCache.end() || cached->second.fingerprint != print) {
            CachedHull entry{print, Polyhedron()};
            if (!computePolyhedron(shape, &entry.poly, whyNot)) return -1;
            cached = m_hullCache.insert_or_assign(shape, std::move(entry)).first;
        }
        s.type = BTG_SHAPE_HULL;
        s.margin = shape->getMargin();
        appendPolyhedron(*this, s, cached->second.poly);
        setLocalAabb(s, shape);
    }
    s.breakingThreshold = relativeThreshold && bad.empty() ? shape->getContactBreakingThreshold(absoluteThreshold)
                                                           : absoluteThreshold;
    int row = int(shapes.size());
    shapes.push_back(s);
    rowOf.emplace(shape, row);
    badReason.push_back(bad);
    shapeOf.push_back(shape);
    fingerprint.push_back(print);
    references.push_back(1);
    m_stale.push_back(0);
    m_grown = true;
    return row;
}

void ShapeTables::beginReferences()
{
    // A row referenced at the last check may be left with no body now: marked stale, so a
    // later reference verifies it first.
    for (size_t r = 0; r < references.size(); ++r) {
        if (references[r] == 0) m_stale[r] = 1;
        references[r] = 0;
    }
}

bool ShapeTables::takeGrown()
{
    const bool grown = m_grown;
    m_grown = false;
    return grown;
}

size_t ShapeTables::unreferenced() const
{
    size_t n = 0;
    for (int r : references) n += r == 0;
    return n;
}

bool ShapeTables::changedSinceBuilt() const
{
    // Every step, over every shape in use (scenes of one shape per body have as many as
    // bodies): in parallel chunks.
    const size_t n = shapeOf.size();
    const size_t minPerThread = 2048;
    std::vector<char> changed(size_t(chunkCount(n, minPerThread)), 0);
    forEachChunk(n, minPerThread, [&](size_t begin, size_t end, int chunk) {
        for (size_t r = begin; r < end; ++r)
            if (references[r] > 0 && shapeFingerprint(shapeOf[r]) != fingerprint[r]) {
                changed[size_t(chunk)] = 1;
                return;
            }
    });
    return std::find(changed.begin(), changed.end(), 1) != changed.end();
}

void ShapeTables::clear()
{
    std::unordered_map<const btCollisionShape*, CachedHull> keep = std::move(m_hullCache);
    const bool relative = relativeThreshold;
    const float absolute = absoluteThreshold;
    *this = ShapeTables();
    m_previousHulls = std::move(keep);
    relativeThreshold = relative;
    absoluteThreshold = absolute;
}

float boundingRadius(const BtgShape& s)
{
    if (s.type == BTG_SHAPE_PLANE) return 0.0f;
    float x = std::max(std::fabs(s.localAabbMin.x), std::fabs(s.localAabbMax.x));
    float y = std::max(std::fabs(s.localAabbMin.y), std::fabs(s.localAabbMax.y));
    float z = std::max(std::fabs(s.localAabbMin.z), std::fabs(s.localAabbMax.z));
    return std::sqrt(x * x + y * y + z * z);
}

}  // namespace btgpu
