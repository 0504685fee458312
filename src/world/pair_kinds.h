// pair_kinds.h — the host's view of the pair-kind table (kernels/shared/pair_kinds.h): its rows
// as data for the plan and the narrowphase launcher, and PairKinds, the set of kinds a scene
// has. Nothing here lists a kind by hand: every row comes from the shared table.
#pragma once
#include "shared/pair_kinds.h"

#include <cstdint>

namespace btgpu {

struct PairKindRow {
    int kind;             // BTG_PAIR_*
    int shapeA, shapeB;   // BTG_SHAPE_*, shapeA <= shapeB
    const char* kernel;   // in `program`; the persistent programs' rows share collide_persistent
    const char* program;  // kernels/<program>.cl
};

// Every row, in table (and launch) order.
extern const PairKindRow kPairKindRows[];
extern const int kNumPairKindRows;

// The row of `kind`, or nullptr for BTG_PAIR_NONE.
const PairKindRow* pairKindRow(int kind);

// A set of pair kinds (bit k: kind k).
struct PairKinds {
    uint32_t mask = 0;
    bool has(int kind) const { return (mask >> kind) & 1u; }
    void add(int kind) { mask |= 1u << kind; }
    bool any() const { return mask != 0; }
    int count() const;
    // Some kind of the set has its kernel in `program`.
    bool anyIn(const char* program) const;
};
static_assert(BTG_NUM_PAIR_KINDS <= 32, "PairKinds holds one bit per kind");

// Whether some pair of these kinds keeps a persistent manifold from substep to substep (the
// buffers gjkPairState and gjkCache, the stage store_persistent_manifolds): the GJK kinds in
// both solvers but those of BTG_SOFT_COLLIDES_AFRESH (two spheres, a box or hull on a plane);
// those, two boxes and convex–mesh pairs only in the bullet mode, since the soft step
// (`speculative`) collides those afresh every substep and keeps nothing. Without any, those
// buffers (256 bytes a pair slot and a contact slot) are not held.
bool keepsPersistentManifolds(const PairKinds& kinds, bool speculative);

}  // namespace btgpu
