// contact_cache.cpp — CPU reference of the contacts stage: compaction in pair order and warm
// start, through the shared btgContactFromManifold / btgFindPrevContact / btgWarmStartFrom,
// and the cache store (btgCachedContactFrom), as the kernels do.
#include "reference/contact_solver_reference.h"

#include <algorithm>

namespace btgpu::ref {

std::vector<BtgContact> buildContactsFromCache(const std::vector<BtgManifold>& manifolds, int pairCount,
                                               const ContactBodies& bodies, const std::vector<BtgCachedContact>& cache,
                                               const BtgStepParams& params)
{
    std::vector<BtgContact> out;
    int n = std::min<int>(pairCount, int(manifolds.size()));
    for (int i = 0; i < n; ++i) {
        const BtgManifold& m = manifolds[i];
        if (m.numPoints <= 0) continue;
        BtgContact c = btgContactFromManifold(m, bodies.pos[m.bodyA], bodies.pos[m.bodyB]);
        int j = btgFindPrevContact(cache.data(), int(cache.size()), m.bodyA, m.bodyB);
        if (j >= 0)
            btgWarmStartFrom(&c, bodies.rot[m.bodyA], cache[j], m.breakingThreshold, params.warmstartFactor);
        out.push_back(c);
    }
    return out;
}

std::vector<BtgContact> buildContacts(const std::vector<BtgManifold>& manifolds, int pairCount,
                                      const ContactBodies& bodies, const std::vector<BtgContact>& prev,
                                      const BtgStepParams& params)
{
    return buildContactsFromCache(manifolds, pairCount, bodies, storeContactCache(prev, bodies), params);
}

std::vector<BtgCachedContact> storeContactCache(const std::vector<BtgContact>& contacts, const ContactBodies& bodies)
{
    std::vector<BtgCachedContact> cache;
    cache.reserve(contacts.size());
    for (const BtgContact& c : contacts) cache.push_back(btgCachedContactFrom(c, bodies.rot[c.bodyA]));
    return cache;
}

}  // namespace btgpu::ref
