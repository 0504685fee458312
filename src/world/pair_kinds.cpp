// pair_kinds.cpp — kPairKindRows, expanded from the shared table, and PairKinds' queries.
#include "world/pair_kinds.h"

#include <cstring>

namespace btgpu {

#define BTGPU_HOST_ROW(program, kind, shapeA, shapeB, routine, kernel) {kind, shapeA, shapeB, #kernel, #program},
const PairKindRow kPairKindRows[] = {BTG_PAIR_KINDS(BTGPU_HOST_ROW)};
#undef BTGPU_HOST_ROW
const int kNumPairKindRows = int(sizeof(kPairKindRows) / sizeof(kPairKindRows[0]));

const PairKindRow* pairKindRow(int kind)
{
    for (int r = 0; r < kNumPairKindRows; ++r)
        if (kPairKindRows[r].kind == kind) return &kPairKindRows[r];
    return nullptr;
}

int PairKinds::count() const
{
    int n = 0;
    for (uint32_t m = mask; m; m &= m - 1) ++n;
    return n;
}

bool PairKinds::anyIn(const char* program) const
{
    for (int r = 0; r < kNumPairKindRows; ++r)
        if (has(kPairKindRows[r].kind) && std::strcmp(kPairKindRows[r].program, program) == 0) return true;
    return false;
}

bool keepsPersistentManifolds(const PairKinds& kinds, bool speculative)
{
    // The soft step (speculative) collides the kinds of BTG_SOFT_COLLIDES_AFRESH afresh; every
    // other GJK kind keeps its manifold in both modes.
    for (int r = 0; r < kNumPairKindRows; ++r)
        if (kinds.has(kPairKindRows[r].kind) && std::strcmp(kPairKindRows[r].program, "narrowphase_gjk") == 0 &&
            !(speculative && BTG_SOFT_COLLIDES_AFRESH(kPairKindRows[r].kind)))
            return true;
    return !speculative && (kinds.anyIn("narrowphase_sat") || kinds.anyIn("narrowphase_mesh"));
}

}  // namespace btgpu
