// contact_cache.cpp — CPU reference of the contacts stage: compaction in pair order and warm
// start, through the shared btgContactFromManifold / btgFindPrevContact / btgWarmStartFrom.
#include "reference/contact_solver_reference.h"

#include <algorithm>

namespace btgpu::ref {

std::vector<BtgContact> buildContacts(const std::vector<BtgManifold>& manifolds, int pairCount,
                                      const ContactBodies& bodies, const std::vector<BtgContact>& prev,
                                      const BtgStepParams& params)
{
    std::vector<BtgContact> out;
    int n = std::min<int>(pairCount, int(manifolds.size()));
    for (int i = 0; i < n; ++i) {
        const BtgManifold& m = manifolds[i];
        if (m.numPoints <= 0) continue;
        BtgContact c = btgContactFromManifold(m, bodies.pos[m.bodyA], bodies.rot[m.bodyA], bodies.pos[m.bodyB]);
        int j = btgFindPrevContact(prev.data(), int(prev.size()), m.bodyA, m.bodyB);
        if (j >= 0) btgWarmStartFrom(&c, prev[j], params.contactThreshold, params.warmstartFactor);
        out.push_back(c);
    }
    return out;
}

}  // namespace btgpu::ref
