// update_activation.cpp (reference) — Bullet's deactivation on the CPU.
#include "reference/update_activation.h"

#include "shared/activation.h"

#include <algorithm>
#include <cstring>

namespace btgpu::reference {

namespace {
float asFloat(uint u)
{
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}
uint asUint(float f)
{
    uint u;
    std::memcpy(&u, &f, 4);
    return u;
}
}  // namespace

void updateActivation(ActivationState& s, const std::vector<BtgEdge>& edges, float dt, float deactivationTime,
                      int rounds, int firstJointEdge)
{
    size_t n = s.props.size();
    std::vector<uint> wake(n, 0u);
    for (size_t i = 0; i < n; ++i) {
        const BtgBodyProps& p = s.props[i];
        if (!btgCanSleep(p.flags)) {
            s.islandTime[i] = BTG_NEVER_UINT;
            continue;
        }
        float own = btgOwnTimer(s.sleepTime[i], s.linVel[i], s.angVel[i], p, dt);
        s.sleepTime[i] = own;
        float island = s.islandTime[i] == BTG_NEVER_UINT ? own : std::fmin(own, asFloat(s.islandTime[i]) + dt);
        s.islandTime[i] = asUint(island);
    }
    if (deactivationTime <= 0.0f) rounds = 0;
    for (int r = 0; r < rounds; ++r) {
        std::vector<uint> dst = s.islandTime;
        for (size_t k = 0; k < edges.size(); ++k) {
            const BtgEdge& c = edges[k];
            uint fa = s.props[c.bodyA].flags, fb = s.props[c.bodyB].flags;
            const bool joint = firstJointEdge >= 0 && k >= size_t(firstJointEdge);
            if (joint) {
                if (btgJointWakes(fa, fb)) wake[c.bodyB] = 1;
                if (btgJointWakes(fb, fa)) wake[c.bodyA] = 1;
            }
            // Joints unite any two dynamic bodies, contacts only bodies that respond.
            if (joint ? btgCanSleep(fa) && btgCanSleep(fb) : btgMergesIslands(fa) && btgMergesIslands(fb)) {
                dst[c.bodyA] = std::min(dst[c.bodyA], s.islandTime[c.bodyB]);
                dst[c.bodyB] = std::min(dst[c.bodyB], s.islandTime[c.bodyA]);
            }
            if (btgWakes(fa, fb, s.sleepTime[c.bodyA])) wake[c.bodyB] = 1;
            if (btgWakes(fb, fa, s.sleepTime[c.bodyB])) wake[c.bodyA] = 1;
        }
        s.islandTime = dst;
    }
    for (size_t i = 0; i < n; ++i) {
        uint f = s.props[i].flags;
        if ((f & BTG_BODY_SLEEPING) && wake[i]) {
            s.props[i].flags = f & ~BTG_BODY_SLEEPING;
            s.sleepTime[i] = 0.0f;
            s.sleepState[i] = 0;
        } else if (btgCanSleep(f) && deactivationTime > 0.0f && asFloat(s.islandTime[i]) > deactivationTime) {
            s.props[i].flags = f | BTG_BODY_SLEEPING;
            s.linVel[i] = s.angVel[i] = btgZero4();
            s.sleepState[i] = 1;
        } else {
            s.sleepState[i] = (f & BTG_BODY_SLEEPING) ? 1 : 0;
        }
    }
}

void wakeTouched(ActivationState& s, const std::vector<BtgContact>& contacts, const std::vector<BtgJoint>& joints)
{
    std::vector<uint> wake(s.props.size(), 0u);
    for (const BtgContact& c : contacts) {
        if (c.numPoints <= 0 || c.bodyA < 0 || c.bodyB < 0) continue;
        const uint fa = s.props[size_t(c.bodyA)].flags, fb = s.props[size_t(c.bodyB)].flags;
        if (btgWakes(fa, fb, s.sleepTime[size_t(c.bodyA)])) wake[size_t(c.bodyB)] = 1u;
        if (btgWakes(fb, fa, s.sleepTime[size_t(c.bodyB)])) wake[size_t(c.bodyA)] = 1u;
    }
    // The joints' closure: a marked body counts as awake, until a pass marks nothing more.
    for (bool changed = true; changed;) {
        changed = false;
        for (const BtgJoint& j : joints) {
            if (!(j.flags & BTG_JOINT_ENABLED) || j.bodyA < 0 || j.bodyB < 0) continue;
            const size_t a = size_t(j.bodyA), b = size_t(j.bodyB);
            const uint fa = wake[a] ? s.props[a].flags & ~BTG_BODY_SLEEPING : s.props[a].flags;
            const uint fb = wake[b] ? s.props[b].flags & ~BTG_BODY_SLEEPING : s.props[b].flags;
            if (btgJointWakes(fa, fb) && !wake[b]) wake[b] = 1u, changed = true;
            if (btgJointWakes(fb, fa) && !wake[a]) wake[a] = 1u, changed = true;
        }
    }
    for (size_t i = 0; i < wake.size(); ++i) {
        if (!wake[i] || !(s.props[i].flags & BTG_BODY_SLEEPING)) continue;
        s.props[i].flags &= ~BTG_BODY_SLEEPING;
        s.sleepTime[i] = 0.0f;
        s.sleepState[i] = 0;
    }
}

}  // namespace btgpu::reference
