// joint_reference.h — CPU references of the joint stages (prepare_joints, finish_joints) and of
// the solve with joints. Each calls the same kernels/shared/joint_*.h functions as its
// kernel, so rows match up to the device's sqrt/divide rounding.
#pragma once
#include "reference/contact_solver_reference.h"
#include "shared/joint_prepare.h"

#include <vector>

namespace btgpu::ref {

struct JointTables {
    std::vector<BtgJoint> joints;
    std::vector<BtgJointState> state;
    std::vector<BtgJointFeedback> feedback;  // per joint (finishJoints sizes it)
    std::vector<BtgJointRow> rows;
};

// Body i as a joint reads it (BTG_JOINT_FIXED_BODY: the fixed body).
BtgJointBody jointBody(const ContactBodies& bodies, int i);

// prepare_joints with `contacts` contact edges before the joints': fills rows and state, returns
// the joints' edges (edge contacts + j is joint j's).
std::vector<BtgEdge> prepareJoints(JointTables& t, const ContactBodies& bodies, const BtgJointStepParams& params);
void finishJoints(JointTables& t, const ContactBodies& bodies, const BtgJointStepParams& params);

// The solve with joints: colors holds every edge's (contacts, then joints); each velocity
// iteration solves the joints' edges color by color, then the contacts', as the device does.
void solveConstraints(std::vector<BtgContact>& contacts, JointTables& t, const std::vector<int>& colors,
                      ContactBodies& bodies, const BtgStepParams& params, int iterations, int jointIterations,
                      int numColors);

}  // namespace btgpu::ref
