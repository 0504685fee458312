/* pair_filter.h — the pairs Bullet's dispatcher never collides although the broadphase finds
 * them: objects that ignore each other's collision check (btCollisionObject::
 * setIgnoreCollisionCheck, which addConstraint's disableCollisionsBetweenLinkedBodies sets
 * between a joint's bodies; needsCollision asks both objects). They are found in the pair
 * list, sorted by (a, b), by binary search. Shared by filter_pairs and its reference. */
#ifndef BTG_PAIR_FILTER_H
#define BTG_PAIR_FILTER_H
#include "prelude.h"
#include "types.h"

static inline int btgPairLess(BtgPair p, BtgPair q)
{
    return p.a < q.a || (p.a == q.a && p.b < q.b);
}

/* Index of the first pair with q's bodies in pairs[0, n) (sorted by (a, b)), -1 when absent. */
static inline int btgFindPair(BTG_CONST_GLOBAL BtgPair* pairs, int n, BtgPair q)
{
    int lo = 0, hi = n;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        BtgPair p = pairs[mid];
        if (btgPairLess(p, q)) lo = mid + 1;
        else hi = mid;
    }
    if (lo < n && pairs[lo].a == q.a && pairs[lo].b == q.b) return lo;
    return -1;
}

#endif
