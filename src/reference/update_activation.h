// update_activation.h (reference) — the deactivation stage on the CPU, same shared rules
// (kernels/shared/activation.h), same double-buffered island rounds over the constraint
// graph's edges.
#pragma once
#include "shared/joint_rows.h"
#include "shared/types.h"

#include <vector>

namespace btgpu::reference {

struct ActivationState {
    std::vector<BtgFloat4> linVel, angVel;
    std::vector<BtgBodyProps> props;
    std::vector<float> sleepTime;
    std::vector<uint> islandTime;  // float bits
    std::vector<uint> sleepState;
};

// Edges from firstJointEdge on are joints' (-1: none).
void updateActivation(ActivationState& s, const std::vector<BtgEdge>& edges, float dt, float deactivationTime,
                      int rounds = 4, int firstJointEdge = -1);

// wake_touched, wake_jointed and wake_apply: before the contacts' rows are made, a sleeping body a
// moving one touches wakes (contacts without points touch nothing), and every sleeping body the
// enabled joints join to an awake or woken one (joints: bodyA, bodyB and flags read).
void wakeTouched(ActivationState& s, const std::vector<BtgContact>& contacts,
                 const std::vector<BtgJoint>& joints = {});

}  // namespace btgpu::reference
