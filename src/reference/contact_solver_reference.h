// contact_solver_reference.h — CPU references of the contact stages (contacts, prepare,
// batching, solve). Each calls the same kernels/shared/contact_rows.h functions as its kernel
// and visits contacts in the order the device's result depends on, so integer stages match
// exactly and float stages up to the device's sqrt/divide rounding.
#pragma once
#include "shared/contact_rows.h"

#include <vector>

namespace btgpu::ref {

// Host copies of the body columns the contact stages use (same meaning as DeviceWorld's).
struct ContactBodies {
    std::vector<BtgFloat4> pos, rot, linVel, angVel, linVel0, angVel0;
    std::vector<BtgFloat4> invInertiaWorld;  // 3 rows per body
    std::vector<BtgFloat4> pushLin, pushAng;
    std::vector<BtgBodyProps> props;
};

// buildContacts: manifolds[0, min(pairCount, size)) with points, in order, warm-started from
// prev (sorted by pair). Returns every contact (the caller compares the count with capacity).
std::vector<BtgContact> buildContacts(const std::vector<BtgManifold>& manifolds, int pairCount,
                                      const ContactBodies& bodies, const std::vector<BtgContact>& prev,
                                      const BtgStepParams& params);

// prepareContacts on every contact of the list.
void prepareContacts(std::vector<BtgContact>& contacts, const ContactBodies& bodies, const BtgStepParams& params);

// colorConstraints: the device's rounds replayed in order; sets every contact's color.
void colorConstraints(std::vector<BtgContact>& contacts, const ContactBodies& bodies, int maxColors);

// solveConstraints: colors in order, contacts of a color in index order; updates linVel/angVel
// and (zeroed first when params.splitImpulse) pushLin/pushAng.
void solveConstraints(std::vector<BtgContact>& contacts, ContactBodies& bodies, const BtgStepParams& params,
                      int iterations, int numColors);

}  // namespace btgpu::ref
