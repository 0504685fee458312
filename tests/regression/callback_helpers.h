// callback_helpers.h — pieces the contact-callback tests share: whether a stage ran on the
// GPU world's last call, and Bullet's internal-edge fix as an app's added callback calls it.
#pragma once
#include "side_by_side.h"

#include <BulletCollision/CollisionDispatch/btInternalEdgeUtility.h>

#include <algorithm>

namespace btgpu::test {

inline bool hasStage(const scenes::Scene& s, const char* name)
{
    const auto& st = s.report()->stages;
    return std::find(st.begin(), st.end(), name) != st.end();
}

// btAdjustInternalEdgeContacts as Bullet's demos call it (the mesh is body 1: the convex side
// first); whether it changed the point's normal.
inline bool adjustInternalEdge(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, const btCollisionObjectWrapper* w1,
                               int partId1, int index1)
{
    const btVector3 n = cp.m_normalWorldOnB;
    btAdjustInternalEdgeContacts(cp, w1, w0, partId1, index1);
    return !(cp.m_normalWorldOnB == n);
}

}  // namespace btgpu::test
