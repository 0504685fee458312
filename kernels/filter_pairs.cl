/* filter_pairs.cl — Stage: filter_pairs (pairs Bullet's needsCollision refuses: objects that
 * ignore each other's collision check, as disableCollisionsBetweenLinkedBodies sets up).
 * Launch: one work-item per ignored pair. After the narrowphase, before the contact list: the
 * pair keeps its slot (the pair list and its kind ranges stay as they are) but its manifold
 * range is emptied, so no contact is made of it, as Bullet's dispatcher makes no manifold.
 * Reads ignored (sorted, a < b), pairs (sorted by (a, b)), counters[kPairCount].
 * Writes pairManifolds[i].count = 0 at the pairs found. */
#include "shared/counters.h"
#include "shared/types.h"
#include "shared/pair_filter.h"

__kernel void filter_ignored_pairs(__global const BtgPair* restrict ignored, int numIgnored,
                                   __global const BtgPair* restrict pairs, __global const uint* restrict counters,
                                   int pairCapacity, __global BtgManifoldRange* pairManifolds)
{
    int k = (int)get_global_id(0);
    if (k >= numIgnored) return;
    const int n = (int)min(counters[BTG_COUNTER_PAIRS], (uint)pairCapacity);
    /* A compound's pair is several child pairs in a row, all with the same bodies. */
    for (int i = btgFindPair(pairs, n, ignored[k]); i >= 0 && i < n && pairs[i].a == ignored[k].a &&
                                                    pairs[i].b == ignored[k].b;
         ++i)
        pairManifolds[i].count = 0;
}
