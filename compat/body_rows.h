// body_rows.h — one Bullet collision object as a device body row: its static properties
// (BtgBodyProps), its state, and the check that its input is usable (finite, sensible mass).
#pragma once
#include "shared/types.h"

#include <string>

class btCollisionObject;

namespace btgpu {

struct BodyState {
    BtgFloat4 pos, rot, linVel, angVel, force, torque;
};

// Properties of `obj` given its shape row and shape; `excluded` sets BTG_BODY_EXCLUDED.
BtgBodyProps bodyProps(const btCollisionObject* obj, int shapeRow, const BtgShape& shape, bool excluded);
BodyState bodyState(const btCollisionObject* obj);
// "" when the body can be simulated, else what is wrong with it.
std::string badInput(const btCollisionObject* obj);
// Stock Bullet's updateSingleAabb rule: a non-static body whose AABB, over its transform and
// (m_useContinuous) its transform predicted dt ahead, measures 1e6 m or more across is taken
// out of the simulation. True when `obj` is such a body now.
bool aabbOverflows(const btCollisionObject* obj, const BtgShape& shape, float dt, bool continuous);

}  // namespace btgpu
