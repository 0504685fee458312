// convex_rows.h — the convex shapes Bullet collides through their support function (capsule,
// cylinder, cone, multi-sphere, convex triangle mesh, uniform scaling of any of those or of a
// box, sphere or hull) turned into BTG_SHAPE_CONVEX rows: the parameters their support
// function reads (kernels/shared/support.h), read off the app's shape, never changed.
#pragma once
#include "shared/types.h"

#include <string>
#include <vector>

class btCollisionShape;

namespace btgpu {

// A shape type served as a BTG_SHAPE_CONVEX row.
bool isSupportShapeType(int type);
// A btConvexHullShape or btConvexPointCloudShape the app gave no polyhedral features: stock
// collides it by GJK, so it is served as a BTG_SHAPE_CONVEX row of its points too.
bool isFeaturelessHull(const btCollisionShape* shape);

// Fills s's type, convexType, upAxis, convexFlags, param and margin (scaled by `factor`, a
// btUniformScalingShape's) and appends its vertex rows to `vertices`; false with *whyNot when
// the shape cannot be taken.
bool convexRow(const btCollisionShape* shape, float factor, BtgShape& s, std::vector<BtgFloat4>& vertices,
               std::string* whyNot);

}  // namespace btgpu
