/* narrowphase_sat.cl — Stage: narrowphase, hull–hull pairs (SAT, then clipping or the
 * closest points of two edges, reduced to at most 4 points; see shared/sat.h and clip.h): the
 * rows of BTG_PAIR_KINDS_NARROWPHASE_SAT (shared/pair_kinds.h) in BTG_NARROWPHASE_KERNEL.
 * Launch: any number of work-items, striding over the kind's range of the kind-grouped pairs
 * (kindRanges[BTG_KIND_RANGE_*(BTG_PAIR_HULL_HULL)], read on the device).
 * Reads pairs, kindOrder, kindRanges, pos, rot, props (shape), shapes, hullVertices/Faces/Indices/Edges.
 * Writes manifolds[slot] for every hull–hull pair slot (numPoints 0 when apart). */
#include "shared/clip.h"
#include "shared/compound.h"

BTG_PAIR_KINDS_NARROWPHASE_SAT(BTG_NARROWPHASE_KERNEL)
