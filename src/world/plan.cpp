// plan.cpp — the plan's stage list, as the pipeline will launch it.
#include "world/plan.h"

namespace btgpu {

std::vector<std::string> Plan::stages() const
{
    std::vector<std::string> s = {"sync_in", "integrate"};
    if (kinds.any()) {
        s.push_back("update_aabbs");
        s.push_back("find_pairs");
        if (kinds.simple()) s.push_back("narrowphase");
        if (kinds.hullHull) s.push_back("narrowphase_sat");
        s.insert(s.end(), {"contact_cache", "prepare_contacts"});
        if (solver == SolverKind::JacobiMassSplitting) s.push_back("solve_jacobi");
        else s.insert(s.end(), {"color_constraints", "solve_constraints"});
    }
    s.insert(s.end(), {"integrate_transforms", "update_activation", "sync_out"});
    return s;
}

}  // namespace btgpu
