// seed_contacts_impl.h — seedContacts (seed_contacts.h): the stock manifolds in the device's
// pair orientation (A the lower row), sorted by body pair as the contact list is.
#pragma once
#include <algorithm>

#include "shared/pair_kinds.h"

namespace btgpu {

BtgCachedContact seededEntry(const StockContact& c, bool swap, int rowA, int rowB);
BtgPersistentManifold seededManifold(const StockContact& c, bool swap, int rowA, int rowB, int kind);

template <class ShapeTypeOf>
int seedContacts(DeviceWorld& w, const std::vector<StockContact>& stock, const RowMap& rows, ShapeTypeOf shapeType)
{
    struct Seed {
        BtgCachedContact entry;
        BtgPersistentManifold manifold;
    };
    std::vector<Seed> seeds;
    for (const StockContact& c : stock) {
        const int r0 = rows.rowOf(c.body0), r1 = rows.rowOf(c.body1);
        if (r0 < 0 || r1 < 0 || r0 == r1) continue;
        const bool swap = r1 < r0;  // the device's pair has the lower row as A
        const int a = swap ? r1 : r0, b = swap ? r0 : r1;
        const int kind = btgPairKind(shapeType(a), shapeType(b));
        if (kind == BTG_PAIR_NONE) continue;
        Seed s;
        s.entry = seededEntry(c, swap, a, b);
        s.manifold = btgIsPersistentKind(kind) ? seededManifold(c, swap, a, b, kind) : BtgPersistentManifold{};
        seeds.push_back(s);
    }
    std::sort(seeds.begin(), seeds.end(), [](const Seed& x, const Seed& y) {
        return x.entry.bodyA != y.entry.bodyA ? x.entry.bodyA < y.entry.bodyA : x.entry.bodyB < y.entry.bodyB;
    });
    const size_t n = std::min(seeds.size(), w.contactCache.capacity());
    if (n == 0) return 0;
    std::vector<BtgCachedContact> cache(w.contactCache.capacity(), BtgCachedContact{});
    w.gjkCache.reserveExact(w.ctx, std::max<size_t>(w.contactCache.capacity(), 1), true);
    std::vector<BtgPersistentManifold> persistent(w.gjkCache.capacity(), BtgPersistentManifold{});
    for (size_t i = 0; i < n; ++i) {
        cache[i] = seeds[i].entry;
        persistent[i] = seeds[i].manifold;
    }
    w.contactCache.upload(w.ctx, cache);
    w.gjkCache.upload(w.ctx, persistent);
    w.gjkCacheCurrent = true;
    w.counters.fill(w.ctx, uint(n), size_t(kPrevContactCount), 1);
    return int(n);
}

}  // namespace btgpu
