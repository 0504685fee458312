/* narrowphase_sat.cl — Stage: narrowphase_sat, two btBoxShapes. The bullet mode (the default
 * solver) collides them as stock's box–box algorithm does (shared/box_box.h: btBoxBoxDetector's
 * points into the pair's persistent manifold, then its refresh); after the solve,
 * store_persistent_manifolds keeps the manifolds for the next substep
 * (shared/persistent_kernels.h), as the GJK program does for its kinds. The soft step
 * (speculative 1) takes each step's SAT clip with its speculative points up to the breaking
 * threshold instead (shared/clip.h), which its substeps need, and keeps no manifold.
 * Launch: collide_persistent (the table's one row) any number of work-items, striding over the kind's range of the
 * kind-grouped pairs (kindRanges[BTG_KIND_RANGE_*(BTG_PAIR_BOX_BOX)], read on the device);
 * store_persistent_manifolds one work-item per contact slot.
 * Reads pairs, kindOrder, kindRanges, pos, rot, props (shape), shapes, children, hull tables,
 * counters, contactCache (to find a pair's previous manifold), gjkCache.
 * Writes manifolds[slot], pairManifolds[slot] and gjkPairState[slot] for every box pair slot
 * (numPoints 0 when apart and nothing kept); then gjkCache (in the warm-start cache's order). */
#include "shared/box_box.h"
#include "shared/clip.h"
#define BTG_PERSISTENT_STEP btgBoxBoxPairStep
#define BTG_SPECULATIVE_COLLIDE btgCollideHullHull
#define BTG_SPECULATIVE_PAIR(kind, shapeA, shapeB) 1
#define BTG_FRESH_KERNEL 0 /* collide_persistent clips the soft step's box pairs itself */
#include "shared/persistent_kernels.h"

BTG_PERSISTENT_PROGRAM_KERNEL(BTG_PAIR_KINDS_NARROWPHASE_SAT)
