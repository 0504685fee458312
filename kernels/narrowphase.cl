/* narrowphase.cl — Stage: narrowphase, the pair kinds that need no SAT: one kernel per row of
 * BTG_PAIR_KINDS_NARROWPHASE (shared/pair_kinds.h), each the row's routine from
 * shared/simple_contacts.h in BTG_NARROWPHASE_KERNEL (shared/narrowphase_common.h).
 * Launch: one work-item per pair slot (pairCapacity); items past counters[kPairCount] and
 * pairs of another kind return at once, so each pair is written by exactly one kernel.
 * Reads pairs, counters, pos, rot, props (shape), shapes, hullVertices/Faces/Indices.
 * Writes manifolds[i] for the pairs of the kernel's kind (numPoints 0 when apart). */
#include "shared/simple_contacts.h"

BTG_PAIR_KINDS_NARROWPHASE(BTG_NARROWPHASE_KERNEL)
