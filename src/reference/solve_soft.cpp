// solve_soft.cpp — CPU reference of the soft step: the device's passes in its order (bodies,
// each gathering its warm start from its edges in index order, or after the first substep
// carrying it; then per color the edges of that
// color in index order; the last color takes the leftovers),
// on contacts only (joints are compared through scenes).
#include "reference/solve_soft.h"

#include "shared/integrate.h"

#include <algorithm>

namespace btgpu::ref {

std::vector<BtgFloat4> solveSoft(std::vector<BtgContact>& contacts, const std::vector<int>& colors,
                                 ContactBodies& bodies, BtgSoftParams params, int numColors,
                                 const std::vector<BtgFrictionDirs>* frictionDirs)
{
    // Bullet's directions of a contact that takes them (one of an anisotropic body), as the
    // kernel reads them: prepare_contacts' scaled ones
    auto dirsOf = [&](size_t e) -> const BtgFrictionDirs* {
        const BtgBodyProps &pa = bodies.props[size_t(contacts[e].bodyA)], &pb = bodies.props[size_t(contacts[e].bodyB)];
        if (!frictionDirs || !btgSoftTakesBulletDirections(pa.flags, pb.flags, params)) return nullptr;
        return &(*frictionDirs)[e];
    };
    if (numColors < 1) numColors = 1;
    const size_t n = bodies.props.size();
    // As soft_color_count and the stage: the substeps the largest edge mass ratio needs.
    float ratio = 0.0f;
    for (const BtgContact& c : contacts) {
        const BtgBodyProps &pa = bodies.props[size_t(c.bodyA)], &pb = bodies.props[size_t(c.bodyB)];
        const float r = btgSoftMassRatio(pa.flags, pa.invMass, pb.flags, pb.invMass);
        if (r > 1.0f) ratio = std::max(ratio, r);
    }
    const int substeps = btgSoftSubstepsFor(params, ratio);
    if (substeps != params.substeps) params = btgSoftParamsWith(params, substeps);
    std::vector<BtgFloat4> rows(BTG_SOFT_BODY_ROWS * n);
    std::vector<BtgSoftContact> soft(contacts.size());
    auto body = [&](int i) {
        return btgMakeSolverBody(bodies.props[i], bodies.invInertiaWorld[3 * i], bodies.invInertiaWorld[3 * i + 1],
                                 bodies.invInertiaWorld[3 * i + 2]);
    };
    // As soft_list_*: each body's edges (dynamic sides of colored contacts), in edge order.
    std::vector<std::vector<uint>> lists(n);
    for (size_t e = 0; e < contacts.size(); ++e) {
        if (colors[e] < 0) continue;
        const int a = contacts[e].bodyA, b = contacts[e].bodyB;
        const bool listA = btgIsSolverDynamic(bodies.props[size_t(a)].flags) != 0;
        const bool listB = btgIsSolverDynamic(bodies.props[size_t(b)].flags) != 0 && b != a;
        if (listA) lists[size_t(a)].push_back(btgSoftContactEntry(int(e), 1, 0));
        if (listB) lists[size_t(b)].push_back(btgSoftContactEntry(int(e), listA ? 0 : 1, 1));
    }
    auto bodyPass = [&](int mode) {
        for (size_t i = 0; i < n; ++i) {
            const uint flags = bodies.props[i].flags;
            BtgFloat4* r = rows.data() + BTG_SOFT_BODY_ROWS * i;
            BtgFloat4 v = bodies.linVel[i], w = bodies.angVel[i];
            if (mode == BTG_SOFT_BODY_BEGIN)
                btgSoftBodyBegin(flags, &v, bodies.linVel0[i], r, params.substeps);
            else if (mode == BTG_SOFT_BODY_VELOCITY)
                btgSoftBodyVelocity(flags, &v, &w, r, !params.gather);
            else if (mode == BTG_SOFT_BODY_CARRY)
                btgSoftBodyCarry(flags, &v, &w, r);
            else
                btgSoftBodyPosition(flags, v, w, r, params.h);
            if (mode == BTG_SOFT_BODY_VELOCITY && btgIsSolverDynamic(flags)) {
                // the substep's warm start, gathered as soft_bodies does
                const BtgSolverBody self = body(int(i));
                BtgBodyVel vel = btgMakeBodyVel(1, v, w);
                for (uint entry : lists[i]) {
                    BtgSoftContact& c = soft[entry >> 2];
                    btgSoftWarmStartSide(&c, int(entry & 1u), self, &vel,
                                         (c.flags & BTG_SOFT_BULLET_DIRECTIONS) ? dirsOf(entry >> 2) : nullptr);
                    if (entry & 2u) btgSoftWarmTotals(&c);
                }
                v = btgMake4(vel.lin.x, vel.lin.y, vel.lin.z, v.w);
                w = btgMake4(vel.ang.x, vel.ang.y, vel.ang.z, w.w);
            }
            if (btgIsSolverDynamic(flags)) {
                bodies.linVel[i] = v;
                bodies.angVel[i] = w;
            }
        }
    };
    auto edge = [&](size_t e, int mode, uint key) {
        const bool warmTotals = (mode & BTG_SOFT_WARM_TOTALS) != 0;
        mode = btgSoftBaseMode(mode);
        if (mode == BTG_SOFT_STORE) {
            btgSoftStore(contacts.data(), int(e), &soft[e]);
            return;
        }
        const int ia = contacts[e].bodyA, ib = contacts[e].bodyB;
        BtgSolverBody a = body(ia), b = body(ib);
        if (mode == BTG_SOFT_PREPARE) {
            const BtgBodyProps& pa = bodies.props[ia];
            const BtgBodyProps& pb = bodies.props[ib];
            const float r = pa.restitution * pb.restitution;
            soft[e] = btgSoftPrepare(contacts[e], a, b, btgMakeBodyVel(a.moving, bodies.linVel0[ia], bodies.angVel0[ia]),
                                     btgMakeBodyVel(b.moving, bodies.linVel0[ib], bodies.angVel0[ib]),
                                     btgMake4(r, r, r, r),
                                     btgContactSolvable(pa.flags, pb.flags), params,
                                     btgPairMaterial(pa, pb), dirsOf(e));
            if (params.heldMassRatio > 0.0f) {
                const int fixed = a.dynamic != b.dynamic && btgContactSolvable(pa.flags, pb.flags);
                const int light = btgSoftLightSide(a, b, params);
                BtgFloat4& rowA = rows[BTG_SOFT_BODY_ROWS * ia + BTG_SOFT_SUPPORT];
                BtgFloat4& rowB = rows[BTG_SOFT_BODY_ROWS * ib + BTG_SOFT_SUPPORT];
                if (a.dynamic) rowA = btgSoftNoteSupport(rowA, fixed, light == 1, int(e));
                if (b.dynamic) rowB = btgSoftNoteSupport(rowB, fixed, light == 2, int(e));
            }
            return;
        }
        BtgBodyVel va = btgMakeBodyVel(a.moving, bodies.linVel[ia], bodies.angVel[ia]);
        BtgBodyVel vb = btgMakeBodyVel(b.moving, bodies.linVel[ib], bodies.angVel[ib]);
        if (mode == BTG_SOFT_RESTITUTION) {
            btgSoftRestitution(&soft[e], a, b, &va, &vb, params);
        } else {
            const BtgFloat4* ra = rows.data() + BTG_SOFT_BODY_ROWS * ia;
            const BtgFloat4* rb = rows.data() + BTG_SOFT_BODY_ROWS * ib;
            // As the kernel: a held pair's normal rows, or a held body's support following its load.
            int normals = 1;
            if (params.heldMassRatio > 0.0f) {
                const int light = btgSoftLightSide(a, b, params);
                if (light) {
                    const BtgFloat4 support = (light == 1 ? ra : rb)[BTG_SOFT_SUPPORT];
                    if (support.x == 1.0f &&
                        btgSoftHeldNormals(&soft[e], light == 1, &soft[size_t(support.y)], a, b, &va, &vb,
                                           btgSoftDeltaOf(ra), btgSoftDeltaOf(rb), mode == BTG_SOFT_SOLVE, params))
                        normals = 0;
                } else if (a.dynamic != b.dynamic && (a.dynamic ? ra : rb)[BTG_SOFT_SUPPORT].z == 1.0f) {
                    normals = 3;
                }
            }
            if (warmTotals)
                btgSoftCarriedTotals(&soft[e], mode == BTG_SOFT_SOLVE,
                                     params.frictionInSolve ? mode == BTG_SOFT_SOLVE : mode == BTG_SOFT_RELAX);
            btgSoftSolve(&soft[e], a, b, &va, &vb, btgSoftDeltaOf(ra), btgSoftDeltaOf(rb), mode == BTG_SOFT_SOLVE,
                         normals, params, btgItemKey(key, uint(e) + 1u),
                         (soft[e].flags & BTG_SOFT_BULLET_DIRECTIONS) ? dirsOf(e) : nullptr);
        }
        if (a.dynamic) {
            bodies.linVel[ia] = btgMake4(va.lin.x, va.lin.y, va.lin.z, bodies.linVel[ia].w);
            bodies.angVel[ia] = btgMake4(va.ang.x, va.ang.y, va.ang.z, bodies.angVel[ia].w);
        }
        if (b.dynamic) {
            bodies.linVel[ib] = btgMake4(vb.lin.x, vb.lin.y, vb.lin.z, bodies.linVel[ib].w);
            bodies.angVel[ib] = btgMake4(vb.ang.x, vb.ang.y, vb.ang.z, bodies.angVel[ib].w);
        }
    };
    // key: a solve or relax sweep's order (SOLVER_RANDMIZE_ORDER): its colours permuted, the
    // leftovers last
    auto edgePass = [&](int mode, uint key) {
        for (int ci = 0; ci < numColors; ++ci) {
            const bool last = ci == numColors - 1;
            const int color = last ? ci : btgPermute(key, numColors - 1, ci);
            for (size_t e = 0; e < contacts.size(); ++e) {
                if (last ? colors[e] < color : colors[e] != color) continue;
                edge(e, mode, key);
            }
        }
    };
    bodyPass(BTG_SOFT_BODY_BEGIN);
    edgePass(BTG_SOFT_PREPARE, 0u);
    for (int s = 0; s < params.substeps; ++s) {
        bodyPass(btgSoftVelocityMode(params, s));  // and the warm start (gathered, or carried)
        edgePass(btgSoftSweepMode(params, s, 0), btgSoftSweepKey(params, s, 0));
        bodyPass(BTG_SOFT_BODY_POSITION);
        edgePass(btgSoftSweepMode(params, s, 1), btgSoftSweepKey(params, s, 1));
    }
    edgePass(BTG_SOFT_RESTITUTION, 0u);
    edgePass(BTG_SOFT_STORE, 0u);
    return rows;
}

void softTransforms(ContactBodies& bodies, const std::vector<BtgFloat4>& rows)
{
    for (size_t i = 0; i < bodies.props.size(); ++i)
        if (btgIsMoving(bodies.props[i].flags)) btgSoftBodyFinish(&bodies.pos[i], &bodies.rot[i], &rows[BTG_SOFT_BODY_ROWS * i]);
}

}  // namespace btgpu::ref
