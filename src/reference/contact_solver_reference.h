// contact_solver_reference.h — CPU references of the contact stages (contacts, prepare,
// batching, solve). Each calls the same kernels/shared/contact_rows.h and solver_rows.h
// functions as its kernel and visits contacts (and the constraint graph's edges) in the order
// the device's result depends on, so integer stages match exactly and float stages up to the
// device's sqrt/divide rounding.
#pragma once
#include "shared/contact_rows.h"
#include "shared/material_rows.h"

#include <vector>

namespace btgpu::ref {

// Host copies of the body columns the contact stages use (same meaning as DeviceWorld's).
struct ContactBodies {
    std::vector<BtgFloat4> pos, rot, linVel, angVel, linVel0, angVel0;
    std::vector<BtgFloat4> invInertiaWorld;  // 3 rows per body
    std::vector<BtgFloat4> pushLin, pushAng;
    std::vector<BtgBodyProps> props;
};

// The pairs' manifold ranges when each pair's one manifold sits at its own slot (today's
// narrowphase: btgOneManifold).
std::vector<BtgManifoldRange> oneManifoldPerPair(const std::vector<BtgManifold>& manifolds);

// The compaction of the ranges of pairs [0, pairCount): each range's manifolds in order, each
// warm-started from the cache (sorted by pair), with the manifold slot it came from. Returns
// every contact (the caller compares the count with capacity).
struct BuiltContacts {
    std::vector<BtgContact> contacts;
    std::vector<uint> manifoldOf;  // per contact: its manifold slot (contactManifolds)
};
BuiltContacts buildContactsFromRanges(const std::vector<BtgManifoldRange>& ranges, const std::vector<BtgManifold>& manifolds,
                                      int pairCount, const ContactBodies& bodies,
                                      const std::vector<BtgCachedContact>& cache, const BtgStepParams& params);
// buildContactsFromCache: manifolds[0, min(pairCount, size)) with points (one per pair), in
// order, warm-started from the cache (sorted by pair).
std::vector<BtgContact> buildContactsFromCache(const std::vector<BtgManifold>& manifolds, int pairCount,
                                               const ContactBodies& bodies, const std::vector<BtgCachedContact>& cache,
                                               const BtgStepParams& params);
// The same, warm-started from the previous step's solved contacts `prev` (sorted by pair), as
// storeContactCache(prev, bodies) keeps them.
std::vector<BtgContact> buildContacts(const std::vector<BtgManifold>& manifolds, int pairCount,
                                      const ContactBodies& bodies, const std::vector<BtgContact>& prev,
                                      const BtgStepParams& params);
// storeContactCache: each contact as the cache keeps it (keys from bodies.rot of body A), with
// the sub-shape keys and feature ids of its manifold manifolds[manifoldOf[i]].
std::vector<BtgCachedContact> storeContactCache(const std::vector<BtgContact>& contacts, const std::vector<uint>& manifoldOf,
                                                const std::vector<BtgManifold>& manifolds, const ContactBodies& bodies);
// A cache from contacts alone (tests that make up a previous step): whole shapes, features
// unknown, so points match by distance only.
std::vector<BtgCachedContact> storeContactCache(const std::vector<BtgContact>& contacts, const ContactBodies& bodies);

// prepareContacts on every contact of the list; returns the contacts' edges of the constraint
// graph (edge i: contact i), as the stage writes them. With BTG_SOLVER_ROLLING_FRICTION and
// `rolling`, each contact's rolling rows there; with BTG_SOLVER_ANISOTROPIC_FRICTION and
// `frictionDirs`, each contact's friction directions; with BTG_SOLVER_FRICTION_ANCHORS and
// `anchors`, each contact's friction anchor targets.
std::vector<BtgEdge> prepareContacts(std::vector<BtgContact>& contacts, const ContactBodies& bodies,
                                     const BtgStepParams& params, std::vector<BtgRollingContact>* rolling = nullptr,
                                     std::vector<BtgFrictionDirs>* frictionDirs = nullptr,
                                     std::vector<BtgFrictionAnchor>* anchors = nullptr);

// colorConstraints: the device's rounds replayed in order; returns every edge's color.
// jointLevels: the bullet mode's ordered joints, edge firstJointEdge + j taking colour
// jointLevels[j] before the contacts bid in it (empty: none).
std::vector<int> colorConstraints(const std::vector<BtgEdge>& edges, const ContactBodies& bodies, int maxColors,
                                  const std::vector<int>& jointLevels = {}, int firstJointEdge = -1);

// solveConstraints: colors in order, the edges (contacts) of a color in index order; colors
// are the edges'; updates linVel/angVel and (zeroed first when params.splitImpulse)
// pushLin/pushAng.
// With rolling rows (BTG_SOLVER_ROLLING_FRICTION) each velocity iteration ends with their sweep;
// with frictionDirs (BTG_SOLVER_ANISOTROPIC_FRICTION) the friction rows take those directions;
// with anchors (BTG_SOLVER_FRICTION_ANCHORS) their positional targets.
void solveConstraints(std::vector<BtgContact>& contacts, const std::vector<int>& colors, ContactBodies& bodies,
                      const BtgStepParams& params, int iterations, int numColors,
                      std::vector<BtgRollingContact>* rolling = nullptr,
                      const std::vector<BtgFrictionDirs>* frictionDirs = nullptr,
                      const std::vector<BtgFrictionAnchor>* anchors = nullptr);

}  // namespace btgpu::ref
