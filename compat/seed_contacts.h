// seed_contacts.h — the GPU path's first step after CPU-path steps continues stock's contacts:
// what stock's algorithms' manifolds hold (taken before they are freed) becomes the device's
// warm-start cache and, for the box and GJK pairs, their persistent manifolds, so points keep
// their impulses and go on persisting as on stock instead of starting anew (one step of
// changed contacts at every return: a CCD hit, a callback's change, a rule that came and went).
#pragma once
#include <btBulletCollisionCommon.h>

#include <vector>

#include "row_map.h"
#include "shared/types.h"
#include "world/device_world.h"

namespace btgpu {

struct StockContact {  // one of stock's manifolds with points, as its algorithm left it
    const btCollisionObject* body0;
    const btCollisionObject* body1;
    int numPoints;
    btManifoldPoint points[MANIFOLD_CACHE_SIZE];
};

// The dispatcher's manifolds with points between two convex, non-compound bodies (the only
// ones the seed continues; other pairs start anew as before).
std::vector<StockContact> takeStockContacts(btDispatcher* dispatcher);

// Writes them into the device world as the previous substep's contacts (rows as rebuilt, each
// row's shape type from shapeType(row)); returns how many were seeded.
template <class ShapeTypeOf>
int seedContacts(DeviceWorld& w, const std::vector<StockContact>& stock, const RowMap& rows, ShapeTypeOf shapeType);

}  // namespace btgpu

#include "seed_contacts_impl.h"
