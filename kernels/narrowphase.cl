/* narrowphase.cl — Stage: narrowphase, the pair kinds that need no SAT: one kernel per row of
 * BTG_PAIR_KINDS_NARROWPHASE (shared/pair_kinds.h), each the row's routine from
 * shared/simple_contacts.h in BTG_NARROWPHASE_KERNEL (shared/narrowphase_common.h).
 * Launch: any number of work-items per kernel, striding over its kind's range of the
 * kind-grouped pairs (kindRanges[BTG_KIND_RANGE_*(kind)], read on the device), so each pair is
 * written by exactly one kernel.
 * Reads pairs, kindOrder, kindRanges, pos, rot, props (shape), shapes, hullVertices/Faces/Indices.
 * Writes manifolds[slot] for the pair slots of the kernel's kind (numPoints 0 when apart). */
#include "shared/compound.h"
#include "shared/simple_contacts.h"

BTG_PAIR_KINDS_NARROWPHASE(BTG_NARROWPHASE_KERNEL)
