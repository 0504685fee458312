/* cache_search.h — finding a manifold's entry in the warm-start cache (the last substep's
 * contacts, in pair order): by bisection, or from a hint near it (btgFindPrevContactNear). Shared
 * by contact_rows.h's users (contact_cache, the persistent-manifold kernels) and their CPU
 * references. */
#ifndef BTG_CACHE_SEARCH_H
#define BTG_CACHE_SEARCH_H
#include "prelude.h"
#include "types.h"

/* Contacts are in pair order, i.e. sorted by (min body, max body): the search key. */
static inline int btgPairKeyLess(int a0, int b0, int a1, int b1)
{
    return a0 < a1 || (a0 == a1 && b0 < b1);
}
/* The warm-start cache's entries are in pair order: the search key is the pair's (min, max). */
static inline int btgCachedPairBelow(BTG_CONST_GLOBAL BtgCachedContact* prev, int j, int ka, int kb)
{
    int ma = prev[j].bodyA, mb = prev[j].bodyB;
    return btgPairKeyLess(ma < mb ? ma : mb, ma < mb ? mb : ma, ka, kb);
}
/* The first entry of prev[lo, hi) whose pair is not below (ka, kb) (hi: none). */
static inline int btgCachedLowerBound(BTG_CONST_GLOBAL BtgCachedContact* prev, int lo, int hi, int ka, int kb)
{
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (btgCachedPairBelow(prev, mid, ka, kb)) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}
/* The same bound found from *hint, a guess near it (the bound of the pair before, for a caller
 * walking pairs in order; or the slot the entry would have if nothing changed since the last
 * substep), by doubling steps from there, forwards or backwards, and bisecting the last; *hint is
 * then this pair's bound. *hint < 0: no hint, plain bisection. Either way the same entry. */
static inline int btgCachedLowerBoundNear(BTG_CONST_GLOBAL BtgCachedContact* prev, int count, int ka, int kb, int* hint)
{
    if (*hint < 0) return btgCachedLowerBound(prev, 0, count, ka, kb);
    int lo = *hint < count ? *hint : count;
    if (lo > 0 && !btgCachedPairBelow(prev, lo - 1, ka, kb)) {
        /* the bound is at or before lo - 1: step back until an entry below the pair */
        int hi = lo - 1, step = 1;
        while (hi - step >= 0 && !btgCachedPairBelow(prev, hi - step, ka, kb)) {
            hi -= step;
            step *= 2;
        }
        lo = btgCachedLowerBound(prev, hi - step + 1 > 0 ? hi - step + 1 : 0, hi, ka, kb);
    } else {
        int step = 1;
        while (lo + step - 1 < count && btgCachedPairBelow(prev, lo + step - 1, ka, kb)) {
            lo += step;
            step *= 2;
        }
        lo = btgCachedLowerBound(prev, lo, lo + step - 1 < count ? lo + step - 1 : count, ka, kb);
    }
    *hint = lo;
    return lo;
}
/* The cached manifold that `m` continues, or -1 (Jolt's CachedBodyPair -> CachedManifold): the
 * entries of m's body pair are consecutive; the one with the same orientation and the same
 * sub-shape keys. */
static inline int btgFindPrevContactNear(BTG_CONST_GLOBAL BtgCachedContact* prev, int count, BtgManifold m, int* hint)
{
    int ka = m.bodyA < m.bodyB ? m.bodyA : m.bodyB, kb = m.bodyA < m.bodyB ? m.bodyB : m.bodyA;
    const int lo = btgCachedLowerBoundNear(prev, count, ka, kb, hint);
    for (int j = lo; j < count; ++j) {
        int ma = prev[j].bodyA, mb = prev[j].bodyB;
        if ((ma < mb ? ma : mb) != ka || (ma < mb ? mb : ma) != kb) break;
        if (ma == m.bodyA && mb == m.bodyB && prev[j].partIdA == m.partIdA && prev[j].indexA == m.indexA &&
            prev[j].partIdB == m.partIdB && prev[j].indexB == m.indexB)
            return j;
    }
    return -1;
}
/* The entries store_contact_cache carries through a sleep beside this substep's n contacts:
 * rank is carry_flags' exclusive scan (the total at cacheCapacity); all or none, none when they
 * would overflow the cache or with carry 0. */
static inline uint btgCarried(BTG_CONST_GLOBAL uint* rank, int carry, uint n, int cacheCapacity)
{
    if (!carry) return 0u;
    const uint k = rank[cacheCapacity];
    return n + k <= (uint)cacheCapacity ? k : 0u;
}
static inline int btgFindPrevContact(BTG_CONST_GLOBAL BtgCachedContact* prev, int count, BtgManifold m)
{
    int none = -1;
    return btgFindPrevContactNear(prev, count, m, &none);
}
#endif
