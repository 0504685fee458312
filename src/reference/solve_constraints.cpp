// solve_constraints.cpp — CPU reference of the solve stage: the same passes as the device
// (warm start, velocity iterations of a normal and a friction sweep, or one interleaved sweep,
// split-impulse iterations),
// colors in order and the edges (contacts) of a color in index order, which is what the batched
// launches compute; with joints, each velocity iteration walks the joints' edges (colors in
// order) before the contacts'.
#include "reference/contact_solver_reference.h"
#include "reference/joint_reference.h"

#include <algorithm>

namespace btgpu::ref {

void solveConstraints(std::vector<BtgContact>& contacts, const std::vector<int>& colors, ContactBodies& bodies,
                      const BtgStepParams& params, int iterations, int numColors, std::vector<BtgRollingContact>* rolling,
                      const std::vector<BtgFrictionDirs>* frictionDirs, const std::vector<BtgFrictionAnchor>* anchors)
{
    const int rows = btgRowFlags(params) & (rolling ? ~0 : ~BTG_ROWS_ROLLING) & (frictionDirs ? ~0 : ~BTG_ROWS_ANISOTROPIC) &
                     (anchors ? ~0 : ~BTG_ROWS_ANCHORS);
    if (numColors < 1) numColors = 1;
    size_t n = bodies.props.size();
    if (params.splitImpulse) {
        bodies.pushLin.assign(n, btgZero4());
        bodies.pushAng.assign(n, btgZero4());
    }
    auto body = [&](int i) {
        return btgMakeSolverBody(bodies.props[i], bodies.invInertiaWorld[3 * i], bodies.invInertiaWorld[3 * i + 1],
                                 bodies.invInertiaWorld[3 * i + 2]);
    };
    auto pass = [&](int mode, int iteration) {
        std::vector<BtgFloat4>& lin = mode == BTG_PASS_PUSH ? bodies.pushLin : bodies.linVel;
        std::vector<BtgFloat4>& ang = mode == BTG_PASS_PUSH ? bodies.pushAng : bodies.angVel;
        // SOLVER_RANDMIZE_ORDER: the sweep's colours and each contact's points permuted
        const uint key = btgPassKey(params.randomSeed, mode, 0, iteration);
        for (int ci = 0; ci < numColors; ++ci) {
            const int color = ci == numColors - 1 ? ci : btgPermute(key, numColors - 1, ci);
            for (size_t e = 0; e < contacts.size(); ++e) {
                const uint order = btgItemKey(key, uint(e) + 1u);
                bool last = color == numColors - 1;  // the serial launch takes higher colors too
                if (last ? colors[e] < color : colors[e] != color) continue;
                BtgContact c = btgLoadContactRows(contacts.data(), int(e), mode == BTG_PASS_ROLLING ? BTG_PASS_NORMALS : mode, rows);
                BtgSolverBody a = body(c.bodyA), b = body(c.bodyB);
                int movingA = mode == BTG_PASS_PUSH ? a.dynamic : a.moving, movingB = mode == BTG_PASS_PUSH ? b.dynamic : b.moving;
                BtgBodyVel va = btgMakeBodyVel(movingA, lin[c.bodyA], ang[c.bodyA]);
                BtgBodyVel vb = btgMakeBodyVel(movingB, lin[c.bodyB], ang[c.bodyB]);
                const BtgFrictionDirs* d = (rows & BTG_ROWS_ANISOTROPIC) ? &(*frictionDirs)[e] : nullptr;
                if (mode == BTG_PASS_WARM_START) btgContactWarmStartDirs(&c, d, a, b, &va, &vb, rows);
                else if (mode == BTG_PASS_NORMALS) btgContactSolveNormalsOrdered(&c, order, a, b, &va, &vb);
                else if (mode == BTG_PASS_FRICTION)
                    btgContactSolveFrictionOrdered(&c, d, (rows & BTG_ROWS_ANCHORS) ? &(*anchors)[e] : nullptr, order, a,
                                                   b, &va, &vb, rows);
                else if (mode == BTG_PASS_VELOCITY)
                    btgContactSolveInterleavedOrdered(&c, d, (rows & BTG_ROWS_ANCHORS) ? &(*anchors)[e] : nullptr, order,
                                                      a, b, &va, &vb, rows);
                else if (mode == BTG_PASS_ROLLING)
                    btgRollingSolve(&(*rolling)[e], c.normal, btgSolvedNormalImpulse(&c), c.numPoints, a, b, &va, &vb);
                else btgContactSolvePushOrdered(&c, order, a, b, &va, &vb);
                if (a.dynamic) {
                    lin[c.bodyA] = btgMake4(va.lin.x, va.lin.y, va.lin.z, lin[c.bodyA].w);
                    ang[c.bodyA] = btgMake4(va.ang.x, va.ang.y, va.ang.z, ang[c.bodyA].w);
                }
                if (b.dynamic) {
                    lin[c.bodyB] = btgMake4(vb.lin.x, vb.lin.y, vb.lin.z, lin[c.bodyB].w);
                    ang[c.bodyB] = btgMake4(vb.ang.x, vb.ang.y, vb.ang.z, ang[c.bodyB].w);
                }
                if (mode != BTG_PASS_ROLLING) btgStoreContactImpulses(contacts.data(), int(e), &c, mode, rows);
            }
        }
    };
    pass(BTG_PASS_WARM_START, -1);
    for (int it = 0; it < iterations; ++it) {
        if (rows & BTG_ROWS_INTERLEAVE) {
            pass(BTG_PASS_VELOCITY, it);
        } else {
            pass(BTG_PASS_NORMALS, it);
            pass(BTG_PASS_FRICTION, it);
        }
        if (rows & BTG_ROWS_ROLLING) pass(BTG_PASS_ROLLING, it);
    }
    if (params.splitImpulse)
        for (int it = 0; it < iterations; ++it) pass(BTG_PASS_PUSH, iterations + it);
}

void solveConstraints(std::vector<BtgContact>& contacts, JointTables& t, const std::vector<int>& colors,
                      ContactBodies& bodies, const BtgStepParams& params, int iterations, int jointIterations,
                      int numColors)
{
    if (numColors < 1) numColors = 1;
    if (params.splitImpulse) {
        bodies.pushLin.assign(bodies.props.size(), btgZero4());
        bodies.pushAng.assign(bodies.props.size(), btgZero4());
    }
    const size_t nc = contacts.size();
    // (rolling rows and anisotropic directions: the contact-only reference)
    const int rows = btgRowFlags(params) & ~(BTG_ROWS_ROLLING | BTG_ROWS_ANISOTROPIC);
    auto body = [&](int i) {
        if (i < 0) return btgFixedJointBody().body;
        return btgMakeSolverBody(bodies.props[i], bodies.invInertiaWorld[3 * i], bodies.invInertiaWorld[3 * i + 1],
                                 bodies.invInertiaWorld[3 * i + 2]);
    };
    auto inColor = [&](size_t e, int color) {
        return color == numColors - 1 ? colors[e] >= color : colors[e] == color;
    };
    auto contactPass = [&](int mode) {
        std::vector<BtgFloat4>& lin = mode == BTG_PASS_PUSH ? bodies.pushLin : bodies.linVel;
        std::vector<BtgFloat4>& ang = mode == BTG_PASS_PUSH ? bodies.pushAng : bodies.angVel;
        for (int color = 0; color < numColors; ++color)
            for (size_t e = 0; e < nc; ++e) {
                if (!inColor(e, color)) continue;
                BtgContact c = btgLoadContactRows(contacts.data(), int(e), mode, rows);
                BtgSolverBody a = body(c.bodyA), b = body(c.bodyB);
                int movingA = mode == BTG_PASS_PUSH ? a.dynamic : a.moving, movingB = mode == BTG_PASS_PUSH ? b.dynamic : b.moving;
                BtgBodyVel va = btgMakeBodyVel(movingA, lin[c.bodyA], ang[c.bodyA]);
                BtgBodyVel vb = btgMakeBodyVel(movingB, lin[c.bodyB], ang[c.bodyB]);
                if (mode == BTG_PASS_WARM_START) btgContactWarmStart(&c, a, b, &va, &vb, rows);
                else if (mode == BTG_PASS_NORMALS) btgContactSolveNormals(&c, a, b, &va, &vb);
                else if (mode == BTG_PASS_FRICTION) btgContactSolveFriction(&c, a, b, &va, &vb, rows);
                else btgContactSolvePush(&c, a, b, &va, &vb);
                if (a.dynamic) {
                    lin[c.bodyA] = btgMake4(va.lin.x, va.lin.y, va.lin.z, lin[c.bodyA].w);
                    ang[c.bodyA] = btgMake4(va.ang.x, va.ang.y, va.ang.z, ang[c.bodyA].w);
                }
                if (b.dynamic) {
                    lin[c.bodyB] = btgMake4(vb.lin.x, vb.lin.y, vb.lin.z, lin[c.bodyB].w);
                    ang[c.bodyB] = btgMake4(vb.ang.x, vb.ang.y, vb.ang.z, ang[c.bodyB].w);
                }
                btgStoreContactImpulses(contacts.data(), int(e), &c, mode, rows);
            }
    };
    auto jointPass = [&](int iteration) {
        for (int color = 0; color < numColors; ++color)
            for (size_t j = 0; j < t.joints.size(); ++j) {
                if (!inColor(nc + j, color)) continue;
                const BtgJoint& joint = t.joints[j];
                if (t.state[j].numRows == 0 || iteration >= joint.iterations) continue;
                BtgSolverBody a = body(joint.bodyA), b = body(joint.bodyB);
                BtgFloat4 zero = btgZero4();
                BtgBodyVel va = btgMakeBodyVel(a.moving, joint.bodyA >= 0 ? bodies.linVel[joint.bodyA] : zero,
                                               joint.bodyA >= 0 ? bodies.angVel[joint.bodyA] : zero);
                BtgBodyVel vb = btgMakeBodyVel(b.moving, joint.bodyB >= 0 ? bodies.linVel[joint.bodyB] : zero,
                                               joint.bodyB >= 0 ? bodies.angVel[joint.bodyB] : zero);
                for (int k = 0; k < t.state[j].numRows; ++k) btgJointRowSolve(&t.rows[joint.firstRow + k], a, b, &va, &vb);
                if (a.dynamic) {
                    bodies.linVel[joint.bodyA] = btgMake4(va.lin.x, va.lin.y, va.lin.z, bodies.linVel[joint.bodyA].w);
                    bodies.angVel[joint.bodyA] = btgMake4(va.ang.x, va.ang.y, va.ang.z, bodies.angVel[joint.bodyA].w);
                }
                if (b.dynamic) {
                    bodies.linVel[joint.bodyB] = btgMake4(vb.lin.x, vb.lin.y, vb.lin.z, bodies.linVel[joint.bodyB].w);
                    bodies.angVel[joint.bodyB] = btgMake4(vb.ang.x, vb.ang.y, vb.ang.z, bodies.angVel[joint.bodyB].w);
                }
            }
    };
    contactPass(BTG_PASS_WARM_START);
    const int velocity = std::max(iterations, t.joints.empty() ? 0 : jointIterations);
    for (int it = 0; it < velocity; ++it) {
        if (!t.joints.empty()) jointPass(it);
        if (it < iterations) {
            contactPass(BTG_PASS_NORMALS);
            contactPass(BTG_PASS_FRICTION);
        }
    }
    if (params.splitImpulse)
        for (int it = 0; it < iterations; ++it) contactPass(BTG_PASS_PUSH);
}

}  // namespace btgpu::ref
