// joint_rows.h — the joints' boundary with Bullet: which btTypedConstraints the GPU path serves
// (by exact type), each joint as a BtgJoint row compared every step with what the device holds
// (what the app changed between steps travels), and the write-back of what stock's
// writeBackJoints leaves: applied impulses, joint feedback, joints broken (setEnabled(false)).
#pragma once
#include "row_map.h"
#include "shared/joint_rows.h"
#include "world/device_world.h"

#include <btBulletDynamicsCommon.h>

#include <string>
#include <vector>

namespace btgpu {

// Why the world's joints keep the CPU path ("" when every one is served): a type other than
// the served ones (subclasses included), a joint built for Bullet's obsolete solve path, a
// joint on a body that is not in the world. Checked when something is added or removed.
std::string jointsStructureReason(const btDiscreteDynamicsWorld& world);
// Per step: Bullet's shared fixed body moved or given mass by the app; a setting turned on
// after the add that no row here builds (the obsolete solve switched on).
std::string jointsStepReason(const btDiscreteDynamicsWorld& world);

// Whether a joint keeps host state that stock's solver updates at each internal step (a
// btHingeAccumulatedAngleConstraint's angle): each internal step is then its own device call.
bool tracksAnglesEachStep(const btDiscreteDynamicsWorld& world);

class JointSync {
public:
    // The world's joints as rows (bodies by row), uploaded where they differ from what the
    // device holds; a joint uploaded anew starts unbroken. Sets w.numJoints, w.jointIterations.
    void upload(btDiscreteDynamicsWorld& world, const RowMap& rows, DeviceWorld& w);
    // After a call: the device's joint state into the constraints, as stock's writeBackJoints.
    void writeBack(DeviceWorld& w);
    // Forget the device's copy (a rebuild or the CPU path ran): everything travels next time.
    void reset()
    {
        m_uploaded.clear();
        m_levelsCurrent = false;
    }

private:
    // Stock's solve order of the joints as colour levels (joint_order.h) into w.jointLevels and
    // w.maxJointLevel, worked out again when the joints or the world's objects changed.
    void uploadLevels(const btDiscreteDynamicsWorld& world, DeviceWorld& w, bool jointsChanged);
    int m_levelObjects = -1;       // the world's objects when the levels were worked out
    bool m_levelsCurrent = false;  // the device holds them
    std::vector<btTypedConstraint*> m_constraints;  // as of the last upload, in world order
    std::vector<BtgJoint> m_uploaded;               // what the device holds
    std::vector<BtgJointState> m_state;             // the device's state as last read
    std::vector<BtgJointFeedback> m_feedback;       // read only while some joint has feedback
    bool m_anyFeedback = false;
};

// One constraint as the device row (firstRow left 0); false when its type is not served.
bool jointRow(const btTypedConstraint& c, const RowMap& rows, int numIterations, BtgJoint* out);

}  // namespace btgpu
