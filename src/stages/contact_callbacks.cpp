// contact_callbacks.cpp — host launchers of the contact-callback stage: the gather of flagged
// pairs' manifolds (one work-item per pair slot; appended by an atomic counter, so the host
// sorts them by slot), the scatter of the ones the host changed, and the materials' second
// preparation (one work-item per contact slot).
#include "stages/contact_callbacks.h"

#include "cl/program.h"

#include <algorithm>

namespace btgpu {

std::vector<GatheredManifold> gatherCallbackManifolds(DeviceWorld& w, bool all)
{
    cl::Context& ctx = w.ctx;
    w.profiler.stage = "contact_callbacks";
    const int pairCapacity = int(std::min(w.pairCapacity, w.pairManifolds.capacity()));
    w.callbackCount.reserve(ctx, 1);
    if (w.callbackSlots.capacity() == 0) {
        w.callbackSlots.reserveExact(ctx, 256);
        w.callbackManifolds.reserveExact(ctx, 256);
        w.callbackAdded.reserveExact(ctx, 256);
    }
    uint count = 0;
    for (int attempt = 0; attempt < 2; ++attempt) {
        const int capacity = int(std::min({w.callbackSlots.capacity(), w.callbackManifolds.capacity(), w.callbackAdded.capacity()}));
        w.callbackCount.fill(ctx, 0u, 0, 1);
        cl::Launch(ctx, ctx.program("contact_callbacks").kernel("gather_callback_manifolds"), &w.profiler)
            .arg(w.pairManifolds).arg(w.manifolds).arg(w.props).arg(w.counters).arg(pairCapacity)
            .arg(w.callbackCount).arg(w.callbackSlots).arg(w.callbackManifolds).arg(capacity).arg(all ? 1 : 0)
            .arg(w.pairs).arg(w.shapes).arg(w.children).arg(w.gjkPairState)
            .arg(int(std::min(w.gjkPairState.capacity(), size_t(pairCapacity)))).arg(w.callbackAdded)
            .run(size_t(std::max(pairCapacity, 1)));
        w.callbackCount.download(ctx, &count, 1);
        if (count <= uint(capacity)) break;
        // More than the buffer holds: grown, and gathered again (the gather only reads).
        const size_t grown = size_t(count) + count / 4 + 64;
        w.callbackSlots.reserveExact(ctx, grown);
        w.callbackManifolds.reserveExact(ctx, grown);
        w.callbackAdded.reserveExact(ctx, grown);
    }
    std::vector<uint> slots(count);
    std::vector<BtgManifold> copies(count);
    std::vector<int> added(count);
    w.callbackSlots.download(ctx, slots.data(), count);
    w.callbackManifolds.download(ctx, copies.data(), count);
    w.callbackAdded.download(ctx, added.data(), count);
    std::vector<GatheredManifold> out(count);
    for (uint i = 0; i < count; ++i) out[i] = {slots[i], copies[i], added[i]};
    std::sort(out.begin(), out.end(), [](const GatheredManifold& a, const GatheredManifold& b) { return a.slot < b.slot; });
    return out;
}

void sendCallbackChanges(DeviceWorld& w, const std::vector<GatheredManifold>& changed,
                         const std::vector<BtgContactMaterial>& materials)
{
    cl::Context& ctx = w.ctx;
    w.profiler.stage = "contact_callbacks";
    if (!changed.empty()) {
        std::vector<uint> slots(changed.size());
        std::vector<BtgManifold> copies(changed.size());
        for (size_t i = 0; i < changed.size(); ++i) {
            slots[i] = changed[i].slot;
            copies[i] = changed[i].manifold;
        }
        // The gather buffers hold at least as many (the changed are among the gathered).
        w.callbackSlots.upload(ctx, slots);
        w.callbackManifolds.upload(ctx, copies);
        cl::Launch(ctx, ctx.program("contact_callbacks").kernel("scatter_callback_manifolds"), &w.profiler)
            .arg(w.callbackSlots).arg(w.callbackManifolds).arg(int(changed.size())).arg(w.manifolds)
            .run(changed.size());
    }
    w.numMaterials = int(materials.size());
    if (!materials.empty()) w.contactMaterials.upload(ctx, materials);
}

std::vector<BtgPair> downloadPairs(DeviceWorld& w)
{
    uint count = 0;
    w.counters.download(w.ctx, &count, 1, size_t(kPairCount));
    const size_t n = std::min<size_t>(count, std::min(w.pairCapacity, w.pairs.capacity()));
    std::vector<BtgPair> pairs(n);
    w.pairs.download(w.ctx, pairs.data(), n);
    return pairs;
}

void clearPairRanges(DeviceWorld& w, const std::vector<uint>& pairs)
{
    if (pairs.empty()) return;
    cl::Context& ctx = w.ctx;
    w.profiler.stage = "contact_callbacks";
    w.callbackSlots.upload(ctx, pairs);
    cl::Launch(ctx, ctx.program("contact_callbacks").kernel("clear_pair_ranges"), &w.profiler)
        .arg(w.callbackSlots).arg(int(pairs.size())).arg(w.pairManifolds).run(pairs.size());
}

void applyContactMaterials(DeviceWorld& w, const BtgStepParams& p)
{
    w.appliedMaterials = std::max(w.numMaterials, 0);  // the soft step's prepare reads them too
    if (w.numMaterials <= 0) return;
    cl::Context& ctx = w.ctx;
    const int contactCapacity = int(std::min({w.contactCapacity, w.contacts.capacity(), w.contactManifolds.capacity()}));
    cl::Launch(ctx, ctx.program("contact_callbacks").kernel("apply_contact_materials"), &w.profiler)
        .arg(w.contacts).arg(w.contactManifolds).arg(w.counters).arg(contactCapacity).arg(w.contactMaterials)
        .arg(w.numMaterials).arg(w.props).arg(w.invInertiaWorld).arg(w.linVel0).arg(w.angVel0).arg(w.linVel)
        .arg(w.angVel).arg(p).run(size_t(std::max(contactCapacity, 1)));
    w.numMaterials = 0;
}

}  // namespace btgpu
