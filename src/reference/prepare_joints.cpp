// prepare_joints.cpp — CPU reference of prepare_joints and finish_joints: each joint in index
// order through the shared functions of joint_prepare.h.
#include "reference/joint_reference.h"

namespace btgpu::ref {

BtgJointBody jointBody(const ContactBodies& bodies, int i)
{
    if (i < 0) return btgFixedJointBody();
    const size_t r = size_t(i);
    return btgMakeJointBody(bodies.props[r], bodies.invInertiaWorld[3 * r], bodies.invInertiaWorld[3 * r + 1],
                            bodies.invInertiaWorld[3 * r + 2], bodies.pos[r], bodies.rot[r], bodies.linVel[r],
                            bodies.angVel[r], bodies.linVel0[r], bodies.angVel0[r]);
}

std::vector<BtgEdge> prepareJoints(JointTables& t, const ContactBodies& bodies, const BtgJointStepParams& params)
{
    std::vector<BtgEdge> edges;
    for (size_t j = 0; j < t.joints.size(); ++j) {
        const BtgJoint& joint = t.joints[j];
        btgPrepareJoint(joint, &t.state[j], t.rows.data(), jointBody(bodies, joint.bodyA), jointBody(bodies, joint.bodyB),
                        params);
        edges.push_back(btgJointEdge(joint, t.state[j].numRows > 0));
    }
    return edges;
}

void finishJoints(JointTables& t, const ContactBodies& bodies, const BtgJointStepParams& params)
{
    t.feedback.resize(t.joints.size(), BtgJointFeedback{});
    for (size_t j = 0; j < t.joints.size(); ++j) {
        const BtgJoint& joint = t.joints[j];
        btgFinishJoint(&t.state[j], &t.feedback[j], joint, t.rows.data(), jointBody(bodies, joint.bodyA), jointBody(bodies, joint.bodyB),
                       params.dt);
    }
}

}  // namespace btgpu::ref
