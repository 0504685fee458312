// contact_callbacks.h — Stage: contact_callbacks (Bullet's gContactAddedCallback on the GPU
// path, kernels/contact_callbacks.cl). Between a substep's contacts and its contact list the
// host gathers the manifolds of pairs with a BTG_BODY_CUSTOM_MATERIAL body, runs the app's
// callback (compat/contact_callbacks.cpp) and sends back what it changed; after
// prepare_contacts the materials it set are applied. Reads pairManifolds, manifolds, props,
// counters; writes callback*, manifolds at the changed slots, contactMaterials, contacts.
#pragma once
#include "world/device_world.h"

#include <vector>

namespace btgpu {

// One flagged manifold as gathered: its slot and its contents; for a pair with a persistent
// manifold (box and GJK pairs) the mask of the identities of the points this substep added or
// replaced (BtgPersistentManifold::addedMask: 0 none), else -2 (every point is this substep's).
struct GatheredManifold {
    uint slot;
    BtgManifold manifold;
    int added = -2;
};
// The manifolds of pairs with a flagged body (all: every manifold with points), sorted by slot
// (blocking: one round trip, a second only when they outgrew the gather buffer).
std::vector<GatheredManifold> gatherCallbackManifolds(DeviceWorld& w, bool all = false);
// The manifolds the host changed back to their slots, and the materials (sorted by slot) for
// applyContactMaterials; both enqueued, not waited for.
void sendCallbackChanges(DeviceWorld& w, const std::vector<GatheredManifold>& changed,
                         const std::vector<BtgContactMaterial>& materials);
// The substep's pairs (after expand_compounds: its collider pairs), blocking.
std::vector<BtgPair> downloadPairs(DeviceWorld& w);
// Pairs (indices into the pair list) that make no contact: their manifold ranges emptied.
void clearPairRanges(DeviceWorld& w, const std::vector<uint>& pairs);
// The substep's contacts whose manifold has a material prepared again with it (a no-op when the
// host sent none); the materials are used once.
void applyContactMaterials(DeviceWorld& w, const BtgStepParams& p);

}  // namespace btgpu
