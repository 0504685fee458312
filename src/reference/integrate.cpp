// integrate.cpp (reference) — the integrate stage on the CPU.
#include "reference/integrate.h"

#include "shared/integrate.h"

namespace btgpu::reference {

void predictMotion(Bodies& b, float dt)
{
    for (size_t i = 0; i < b.props.size(); ++i) {
        if (!btgIsMoving(b.props[i].flags)) continue;
        b.linVel[i] = btgDamp(b.linVel[i], b.props[i].linearDamping, dt);
        b.angVel[i] = btgDamp(b.angVel[i], b.props[i].angularDamping, dt);
        btgAdditionalDamping(&b.linVel[i], &b.angVel[i], b.props[i]);
    }
}

void applyForces(Bodies& b, float dt, std::vector<BtgFloat4>& iw, float maxGyroscopicForce)
{
    iw.assign(3 * b.props.size(), btgZero4());
    for (size_t i = 0; i < b.props.size(); ++i) {
        const BtgBodyProps& p = b.props[i];
        BtgFloat4 inv = (p.flags & BTG_BODY_DYNAMIC) ? p.invInertiaLocal : btgZero4();
        BtgMat3 m = btgInvInertiaWorld(b.rot[i], inv);
        iw[3 * i] = m.r0;
        iw[3 * i + 1] = m.r1;
        iw[3 * i + 2] = m.r2;
        if (!btgIsMoving(p.flags)) continue;
        BtgFloat4 w = b.angVel[i];
        b.linVel[i] = btgApplyLinearForces(b.linVel[i], b.extForce[i], p, dt);
        b.angVel[i] = btgApplyAngularForces(w, b.extTorque[i], b.rot[i], m, p, dt, maxGyroscopicForce);
    }
}

void integrateTransforms(Bodies& b, float dt, float turnErp)
{
    for (size_t i = 0; i < b.props.size(); ++i) {
        if (!btgIsMoving(b.props[i].flags)) continue;
        BtgFloat4 x = b.pos[i], q = b.rot[i], pl = b.pushLin[i], pa = b.pushAng[i];
        if (pl.x != 0.0f || pl.y != 0.0f || pl.z != 0.0f || pa.x != 0.0f || pa.y != 0.0f || pa.z != 0.0f) {
            x = btgXyz(x) + btgXyz(pl) * dt;
            q = btgIntegrateRotation(q, btgXyz(pa) * turnErp, dt);
        }
        b.pos[i] = btgXyz(x) + btgXyz(b.linVel[i]) * dt;
        b.rot[i] = btgIntegrateRotation(q, b.angVel[i], dt);
    }
}

}  // namespace btgpu::reference
