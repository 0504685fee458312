// contact_callbacks.h (reference) — the contact-callback stage on the CPU: the flagged pairs'
// manifolds in slot order, and the contacts prepared again with the host's materials
// (kernels/shared/contact_material.h, the same functions as the kernels).
#pragma once
#include "shared/contact_material.h"

#include <vector>

namespace btgpu::ref {

// Slots of the manifolds with points, of the first pairCount pairs' ranges, with a flagged body.
std::vector<uint> gatherCallbackManifolds(const std::vector<BtgManifoldRange>& pairManifolds, uint pairCount,
                                          const std::vector<BtgManifold>& manifolds,
                                          const std::vector<BtgBodyProps>& props, bool all = false);

// Contacts [0, count) whose manifold slot has a material (materials sorted by slot), prepared again.
void applyContactMaterials(std::vector<BtgContact>& contacts, const std::vector<uint>& contactManifolds, size_t count,
                           const std::vector<BtgContactMaterial>& materials, const std::vector<BtgBodyProps>& props,
                           const std::vector<BtgFloat4>& invInertiaWorld, const std::vector<BtgFloat4>& linVel0,
                           const std::vector<BtgFloat4>& angVel0, const std::vector<BtgFloat4>& linVel,
                           const std::vector<BtgFloat4>& angVel, const BtgStepParams& params);

}  // namespace btgpu::ref
