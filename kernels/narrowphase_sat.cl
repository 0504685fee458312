/* narrowphase_sat.cl — Stage: narrowphase, hull–hull pairs (SAT, then clipping or the
 * closest points of two edges, reduced to at most 4 points; see shared/sat.h and clip.h): the
 * rows of BTG_PAIR_KINDS_NARROWPHASE_SAT (shared/pair_kinds.h) in BTG_NARROWPHASE_KERNEL.
 * Launch: one work-item per pair slot (pairCapacity); items past counters[kPairCount] and
 * pairs that are not hull–hull return at once.
 * Reads pairs, counters, pos, rot, props (shape), shapes, hullVertices/Faces/Indices/Edges.
 * Writes manifolds[i] for every hull–hull pair i (numPoints 0 when apart). */
#include "shared/clip.h"

BTG_PAIR_KINDS_NARROWPHASE_SAT(BTG_NARROWPHASE_KERNEL)
