// solve_jacobi.cpp (reference) — the Jacobi solve on the CPU: all contacts of a pass against
// the same velocities, then each body's copies averaged in its list's order, as on the device.
#include "reference/solve_jacobi.h"

#include "shared/jacobi_rows.h"

namespace btgpu::ref {

namespace {
bool sideListed(const ContactBodies& bodies, const BtgContact& c, int side)
{
    uint fa = bodies.props[c.bodyA].flags, fb = bodies.props[c.bodyB].flags;
    return btgContactSolvable(fa, fb) && btgIsSolverDynamic(side == 0 ? fa : fb);
}
}  // namespace

JacobiLists jacobiLists(const std::vector<BtgContact>& contacts, const ContactBodies& bodies)
{
    size_t n = bodies.props.size();
    JacobiLists l;
    std::vector<uint> count(n, 0u);
    for (const BtgContact& c : contacts)
        for (int side = 0; side < 2; ++side)
            if (sideListed(bodies, c, side)) ++count[side == 0 ? c.bodyA : c.bodyB];
    l.start.assign(n + 1, 0u);
    for (size_t b = 0; b < n; ++b) l.start[b + 1] = l.start[b] + count[b];
    l.entries.assign(l.start[n], 0u);
    std::vector<uint> cursor(l.start.begin(), l.start.end() - 1);
    // Visiting entries in increasing order fills each list already sorted.
    for (size_t i = 0; i < contacts.size(); ++i)
        for (int side = 0; side < 2; ++side)
            if (sideListed(bodies, contacts[i], side))
                l.entries[cursor[side == 0 ? contacts[i].bodyA : contacts[i].bodyB]++] = uint(2 * i + side);
    return l;
}

void solveJacobi(std::vector<BtgContact>& contacts, ContactBodies& bodies, const BtgStepParams& params, int iterations)
{
    size_t n = bodies.props.size();
    if (params.splitImpulse) {
        bodies.pushLin.assign(n, btgZero4());
        bodies.pushAng.assign(n, btgZero4());
    }
    JacobiLists l = jacobiLists(contacts, bodies);
    auto body = [&](int i) {
        BtgSolverBody b = btgMakeSolverBody(bodies.props[i], bodies.invInertiaWorld[3 * i], bodies.invInertiaWorld[3 * i + 1],
                                            bodies.invInertiaWorld[3 * i + 2]);
        return b.dynamic ? btgSplitBody(b, l.start[i + 1] - l.start[i]) : b;
    };
    std::vector<BtgFloat4> deltas(4 * contacts.size(), btgZero4());
    auto pass = [&](int mode) {
        std::vector<BtgFloat4>& lin = mode == BTG_PASS_PUSH ? bodies.pushLin : bodies.linVel;
        std::vector<BtgFloat4>& ang = mode == BTG_PASS_PUSH ? bodies.pushAng : bodies.angVel;
        for (size_t i = 0; i < contacts.size(); ++i) {
            BtgContact& c = contacts[i];
            BtgSolverBody a = body(c.bodyA), b = body(c.bodyB);
            int movingA = mode == BTG_PASS_PUSH ? a.dynamic : a.moving, movingB = mode == BTG_PASS_PUSH ? b.dynamic : b.moving;
            BtgBodyVel dA, dB;
            btgJacobiContact(&c, a, b, btgMakeBodyVel(movingA, lin[c.bodyA], ang[c.bodyA]),
                             btgMakeBodyVel(movingB, lin[c.bodyB], ang[c.bodyB]), mode, &dA, &dB);
            deltas[4 * i] = dA.lin;
            deltas[4 * i + 1] = dA.ang;
            deltas[4 * i + 2] = dB.lin;
            deltas[4 * i + 3] = dB.ang;
        }
        for (size_t b = 0; b < n; ++b) {
            uint lo = l.start[b], hi = l.start[b + 1];
            if (hi == lo) continue;
            BtgFloat4 sl = btgZero4(), sa = btgZero4();
            for (uint k = lo; k < hi; ++k) {
                sl = sl + deltas[2 * l.entries[k]];
                sa = sa + deltas[2 * l.entries[k] + 1];
            }
            lin[b] = btgJacobiAverage(lin[b], sl, hi - lo);
            ang[b] = btgJacobiAverage(ang[b], sa, hi - lo);
        }
    };
    pass(BTG_PASS_WARM_START);
    for (int it = 0; it < iterations; ++it) pass(BTG_PASS_VELOCITY);
    if (params.splitImpulse)
        for (int it = 0; it < iterations; ++it) pass(BTG_PASS_PUSH);
}

}  // namespace btgpu::ref
