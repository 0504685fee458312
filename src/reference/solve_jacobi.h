// solve_jacobi.h (reference) — CPU reference of the Jacobi mass-splitting solve: the oracle for
// kernels/solve_jacobi.cl, calling the same kernels/shared/jacobi_rows.h functions.
#pragma once
#include "reference/contact_solver_reference.h"

namespace btgpu::ref {

// Each dynamic body's solvable contacts as entries 2 * contact + side, in increasing order
// (what jacobi_count/fill/sort_lists build): start has numBodies + 1 offsets into entries.
struct JacobiLists {
    std::vector<uint> start, entries;
};
JacobiLists jacobiLists(const std::vector<BtgContact>& contacts, const ContactBodies& bodies);

// solveJacobi: warm start, `iterations` velocity passes, and (zeroing pushLin/pushAng first
// when params.splitImpulse) `iterations` push passes; every contact of a pass sees the
// velocities of the previous pass. Colors are ignored.
void solveJacobi(std::vector<BtgContact>& contacts, ContactBodies& bodies, const BtgStepParams& params, int iterations);

}  // namespace btgpu::ref
