// broadphase_leaves.h (reference) — CPU versions of the broadphase_leaves kernels, calling the
// same shared functions: the leaves' update, the overlapping leaf pairs in (a, b) order with
// m_newpairs, and the difference of two sorted lists.
#pragma once
#include "shared/types.h"

#include <vector>

namespace btgpu::ref {

// One substep's leaves_update over every row; returns how many leaves moved (moved[r] set to 1).
int updateLeaves(const std::vector<BtgFloat4>& pos, const std::vector<BtgFloat4>& rot,
                 const std::vector<BtgFloat4>& linVel, const std::vector<BtgFloat4>& angVel,
                 const std::vector<BtgBodyProps>& props, const std::vector<BtgShape>& shapes, float threshold, float dt,
                 bool continuous, bool reset, std::vector<BtgFloat4>& leafMin, std::vector<BtgFloat4>& leafMax,
                 std::vector<BtgFloat4>& oldMin, std::vector<BtgFloat4>& oldMax, std::vector<unsigned>& moved);

// The allowed pairs whose leaves overlap, sorted by (a, b); *newPairs: stock's m_newpairs less
// one (btgLeafJudge over every two rows); *transient: the allowed pairs stock's pass met whose
// leaves no longer overlap, sorted.
std::vector<BtgPair> leafPairs(const std::vector<BtgBodyProps>& props, const std::vector<BtgFloat4>& leafMin,
                               const std::vector<BtgFloat4>& leafMax, const std::vector<BtgFloat4>& oldMin,
                               const std::vector<BtgFloat4>& oldMax, const std::vector<unsigned>& moved,
                               unsigned* newPairs, std::vector<BtgPair>* transient);

// Pairs of `next` not in `prev` (in next's order) and of `prev` not in `next` (in prev's order).
void leafDiff(const std::vector<BtgPair>& next, const std::vector<BtgPair>& prev, std::vector<BtgPair>* added,
              std::vector<BtgPair>* removed);

}  // namespace btgpu::ref
