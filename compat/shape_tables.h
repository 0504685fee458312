// shape_tables.h — Bullet collision shapes turned into the GPU shape table and hull tables.
// Boxes become 8-vertex hulls (margin inside the extents, as btBoxShape), convex hulls use
// Bullet's own polyhedral features (margin kept as an outward rounding), spheres and static
// planes are parameters. Anything else is refused with a reason (the world then runs on the
// CPU path).
#pragma once
#include "shared/types.h"

#include <string>
#include <unordered_map>
#include <vector>

class btCollisionShape;

namespace btgpu {

struct ShapeTables {
    std::vector<BtgShape> shapes;
    std::vector<BtgFloat4> vertices;
    std::vector<BtgFace> faces;
    std::vector<int> indices;
    std::vector<BtgFloat4> edges;
    std::unordered_map<const btCollisionShape*, int> rowOf;

    // The shape's row (adding it the first time), or -1 with *whyNot set.
    int add(const btCollisionShape* shape, std::string* whyNot);
    void clear() { *this = ShapeTables(); }
};

// Radius of a sphere about the body origin that holds the shape (m); planes: 0.
float boundingRadius(const BtgShape& s);

}  // namespace btgpu
