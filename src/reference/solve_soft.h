// solve_soft.h (reference) — CPU reference of the soft step (contacts only): the oracle for
// kernels/solve_soft.cl, calling the same kernels/shared/soft_rows.h functions, colors in order
// and the edges of a color in index order (the last color takes every higher one).
#pragma once
#include "reference/contact_solver_reference.h"
#include "shared/soft_held_rows.h"

namespace btgpu::ref {

// solveSoft: bodies begin, contacts prepare, `params.substeps` substeps (raised as the stage
// raises them for the largest mass ratio, btgSoftSubstepsFor) (velocities, warm
// start, solve, positions, relax), restitution, store. Updates linVel/angVel and the contacts'
// impulses; returns the bodies' soft rows (BTG_SOFT_BODY_ROWS each) for softTransforms. frictionDirs:
// prepare_contacts' directions per contact, read with params.anisotropic.
std::vector<BtgFloat4> solveSoft(std::vector<BtgContact>& contacts, const std::vector<int>& colors,
                                 ContactBodies& bodies, BtgSoftParams params, int numColors,
                                 const std::vector<BtgFrictionDirs>* frictionDirs = nullptr);
// softTransforms: the poses of the bodies the integrator moves, from their rows.
void softTransforms(ContactBodies& bodies, const std::vector<BtgFloat4>& rows);

}  // namespace btgpu::ref
