// contact_callbacks.cpp (reference) — see contact_callbacks.h.
#include "reference/contact_callbacks.h"

#include <algorithm>

namespace btgpu::ref {

std::vector<uint> gatherCallbackManifolds(const std::vector<BtgManifoldRange>& pairManifolds, uint pairCount,
                                          const std::vector<BtgManifold>& manifolds,
                                          const std::vector<BtgBodyProps>& props, bool all)
{
    std::vector<uint> slots;
    for (uint i = 0; i < pairCount && i < pairManifolds.size(); ++i) {
        const BtgManifoldRange r = pairManifolds[i];
        for (int j = r.start; j < r.start + r.count; ++j) {
            const BtgManifold& m = manifolds[size_t(j)];
            if (m.numPoints <= 0) continue;
            if (all || (props[size_t(m.bodyA)].flags | props[size_t(m.bodyB)].flags) & BTG_BODY_CUSTOM_MATERIAL)
                slots.push_back(uint(j));
        }
    }
    std::sort(slots.begin(), slots.end());
    return slots;
}

void applyContactMaterials(std::vector<BtgContact>& contacts, const std::vector<uint>& contactManifolds, size_t count,
                           const std::vector<BtgContactMaterial>& materials, const std::vector<BtgBodyProps>& props,
                           const std::vector<BtgFloat4>& invInertiaWorld, const std::vector<BtgFloat4>& linVel0,
                           const std::vector<BtgFloat4>& angVel0, const std::vector<BtgFloat4>& linVel,
                           const std::vector<BtgFloat4>& angVel, const BtgStepParams& params)
{
    for (size_t i = 0; i < count && i < contacts.size(); ++i) {
        const int found = btgFindMaterial(materials.data(), int(materials.size()), contactManifolds[i]);
        if (found < 0) continue;
        BtgContact& c = contacts[i];
        const BtgBodyProps& pa = props[size_t(c.bodyA)];
        const BtgBodyProps& pb = props[size_t(c.bodyB)];
        const size_t ia = 3 * size_t(c.bodyA), ib = 3 * size_t(c.bodyB);
        BtgSolverBody a = btgMakeSolverBody(pa, invInertiaWorld[ia], invInertiaWorld[ia + 1], invInertiaWorld[ia + 2]);
        BtgSolverBody b = btgMakeSolverBody(pb, invInertiaWorld[ib], invInertiaWorld[ib + 1], invInertiaWorld[ib + 2]);
        BtgBodyVel a0 = btgMakeBodyVel(a.moving, linVel0[size_t(c.bodyA)], angVel0[size_t(c.bodyA)]);
        BtgBodyVel b0 = btgMakeBodyVel(b.moving, linVel0[size_t(c.bodyB)], angVel0[size_t(c.bodyB)]);
        BtgBodyVel a1 = btgMakeBodyVel(a.moving, linVel[size_t(c.bodyA)], angVel[size_t(c.bodyA)]);
        BtgBodyVel b1 = btgMakeBodyVel(b.moving, linVel[size_t(c.bodyB)], angVel[size_t(c.bodyB)]);
        btgApplyContactMaterial(&c, materials[size_t(found)], btgPairMaterial(pa, pb), a, b, a0, b0, a1, b1,
                                btgContactSolvable(pa.flags, pb.flags), params);
    }
}

}  // namespace btgpu::ref
