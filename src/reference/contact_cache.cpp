// contact_cache.cpp — CPU reference of the contacts stage: compaction of the pairs' manifold
// ranges in pair order and warm start, through the shared btgContactFromManifold /
// btgFindPrevContact / btgWarmStartFrom, and the cache store (btgCachedContactFrom), as the
// kernels do.
#include "reference/contact_solver_reference.h"
#include "shared/narrowphase_common.h"

#include <algorithm>

namespace btgpu::ref {

std::vector<BtgManifoldRange> oneManifoldPerPair(const std::vector<BtgManifold>& manifolds)
{
    std::vector<BtgManifoldRange> ranges;
    ranges.reserve(manifolds.size());
    for (size_t i = 0; i < manifolds.size(); ++i) ranges.push_back(btgOneManifold(int(i), manifolds[i]));
    return ranges;
}

BuiltContacts buildContactsFromRanges(const std::vector<BtgManifoldRange>& ranges, const std::vector<BtgManifold>& manifolds,
                                      int pairCount, const ContactBodies& bodies,
                                      const std::vector<BtgCachedContact>& cache, const BtgStepParams& params)
{
    BuiltContacts out;
    int n = std::min<int>(pairCount, int(ranges.size()));
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < ranges[i].count; ++j) {
            const uint slot = uint(ranges[i].start + j);
            const BtgManifold& m = manifolds[slot];
            BtgContact c = btgContactFromManifold(m, bodies.pos[m.bodyA], bodies.pos[m.bodyB]);
            int prev = btgFindPrevContact(cache.data(), int(cache.size()), m);
            const float processing = (params.solverFlags & BTG_SOLVER_PROCESSING_THRESHOLD)
                                         ? btgProcessingThreshold(bodies.props[m.bodyA], bodies.props[m.bodyB])
                                         : BTG_NO_PROCESSING_THRESHOLD;
            if (prev >= 0) btgWarmStartFrom(&c, bodies.rot[m.bodyA], m, cache[prev], params.warmstartFactor, processing,
                                             (params.solverFlags & BTG_SOLVER_WARM_FRICTION) != 0u);
            out.contacts.push_back(c);
            out.manifoldOf.push_back(slot);
        }
    }
    return out;
}

std::vector<BtgContact> buildContactsFromCache(const std::vector<BtgManifold>& manifolds, int pairCount,
                                               const ContactBodies& bodies, const std::vector<BtgCachedContact>& cache,
                                               const BtgStepParams& params)
{
    return buildContactsFromRanges(oneManifoldPerPair(manifolds), manifolds, pairCount, bodies, cache, params).contacts;
}

std::vector<BtgContact> buildContacts(const std::vector<BtgManifold>& manifolds, int pairCount,
                                      const ContactBodies& bodies, const std::vector<BtgContact>& prev,
                                      const BtgStepParams& params)
{
    return buildContactsFromCache(manifolds, pairCount, bodies, storeContactCache(prev, bodies), params);
}

std::vector<BtgCachedContact> storeContactCache(const std::vector<BtgContact>& contacts, const std::vector<uint>& manifoldOf,
                                                const std::vector<BtgManifold>& manifolds, const ContactBodies& bodies)
{
    std::vector<BtgCachedContact> cache;
    cache.reserve(contacts.size());
    for (size_t i = 0; i < contacts.size(); ++i)
        cache.push_back(btgCachedContactFrom(contacts[i], bodies.rot[contacts[i].bodyA], &manifolds[manifoldOf[i]]));
    return cache;
}

std::vector<BtgCachedContact> storeContactCache(const std::vector<BtgContact>& contacts, const ContactBodies& bodies)
{
    std::vector<BtgCachedContact> cache;
    cache.reserve(contacts.size());
    for (const BtgContact& c : contacts) {
        BtgManifold whole = btgEmptyManifold(c.bodyA, c.bodyB);  // features unknown
        cache.push_back(btgCachedContactFrom(c, bodies.rot[c.bodyA], &whole));
    }
    return cache;
}

}  // namespace btgpu::ref
