// leaf_pairs.h — stock's pair cache as the device's leaf pairs make it (stage broadphase_leaves):
// a pair joins when its Dbvt leaves come to overlap, and leaves as btDbvtBroadphase::collide's
// lazy cleanup drops it: a round-robin share of the pair array a step (max(m_newpairs, 10 % of
// the pairs), from where the last step stopped), only pairs whose leaves no longer overlap,
// the last pair moved into the hole as btHashedOverlappingPairCache does.
#pragma once
#include "stages/broadphase_leaves.h"

#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace btgpu {

class LeafPairCache {
public:
    // Rows re-uploaded: the device starts its leaves afresh, and so does the cache.
    void clear();
    // One device call's change; `steps`: the internal steps it ran (each a round of the cleanup).
    void apply(const LeafChanges& changes, int steps);
    // The pair array (rows, a < b) in stock's cache order as far as it is followed: new pairs at
    // the end, removals filled from the end.
    const std::vector<BtgPair>& pairs() const { return m_pairs; }
    // The last apply's pairs that joined and left the cache (in that order), and whether it was
    // the first since clear() (every pair joined).
    const std::vector<BtgPair>& joined() const { return m_joined; }
    const std::vector<BtgPair>& left() const { return m_left; }
    bool fresh() const { return m_fresh; }

private:
    static std::uint64_t key(const BtgPair& p) { return (std::uint64_t(unsigned(p.a)) << 32) | unsigned(p.b); }
    void removeAt(size_t at);

    std::vector<BtgPair> m_pairs;
    std::unordered_map<std::uint64_t, size_t> m_index;  // place of each pair in m_pairs
    std::unordered_set<std::uint64_t> m_overlapping;    // pairs whose leaves overlap (the device's list)
    int m_cid = 0;  // btDbvtBroadphase::m_cid
    std::vector<BtgPair> m_joined, m_left;
    bool m_cleared = true, m_fresh = false;
};

}  // namespace btgpu
