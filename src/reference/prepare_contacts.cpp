// prepare_contacts.cpp — CPU reference of the prepare stage (btgPrepareContact per contact, its
// rolling rows with rolling friction, and the contacts' graph edges).
#include "reference/contact_solver_reference.h"

namespace btgpu::ref {

namespace {
BtgSolverBody solverBody(const ContactBodies& b, int i)
{
    return btgMakeSolverBody(b.props[i], b.invInertiaWorld[3 * i], b.invInertiaWorld[3 * i + 1], b.invInertiaWorld[3 * i + 2]);
}
}  // namespace

std::vector<BtgEdge> prepareContacts(std::vector<BtgContact>& contacts, const ContactBodies& bodies,
                                     const BtgStepParams& params, std::vector<BtgRollingContact>* rolling,
                                     std::vector<BtgFrictionDirs>* frictionDirs, std::vector<BtgFrictionAnchor>* anchors)
{
    std::vector<BtgEdge> edges;
    if (rolling) rolling->clear();
    if (frictionDirs) frictionDirs->clear();
    if (anchors) anchors->clear();
    for (BtgContact& c : contacts) {
        edges.push_back(btgContactEdge(c));
        const BtgBodyProps& pa = bodies.props[c.bodyA];
        const BtgBodyProps& pb = bodies.props[c.bodyB];
        BtgSolverBody a = solverBody(bodies, c.bodyA), b = solverBody(bodies, c.bodyB);
        BtgBodyVel a0 = btgMakeBodyVel(a.moving, bodies.linVel0[c.bodyA], bodies.angVel0[c.bodyA]);
        BtgBodyVel b0 = btgMakeBodyVel(b.moving, bodies.linVel0[c.bodyB], bodies.angVel0[c.bodyB]);
        BtgBodyVel a1 = btgMakeBodyVel(a.moving, bodies.linVel[c.bodyA], bodies.angVel[c.bodyA]);
        BtgBodyVel b1 = btgMakeBodyVel(b.moving, bodies.linVel[c.bodyB], bodies.angVel[c.bodyB]);
        const BtgPairMaterial mat = btgPairMaterial(pa, pb);
        const int solvable = btgContactSolvable(pa.flags, pb.flags);
        btgPrepareContact(&c, a, b, a0, b0, a1, b1, mat, solvable, params);
        BtgFrictionDirs dirs;
        const bool anisotropic = frictionDirs && (params.solverFlags & BTG_SOLVER_ANISOTROPIC_FRICTION);
        if (anisotropic) {
            btgPrepareAnisotropicFriction(&c, &dirs, a, b, a1, b1, bodies.rot[c.bodyA], bodies.rot[c.bodyB], pa, pb,
                                          solvable, params);
            frictionDirs->push_back(dirs);
        }
        if (anchors && (params.solverFlags & BTG_SOLVER_FRICTION_ANCHORS))
            anchors->push_back(btgPrepareFrictionAnchor(&c, anisotropic ? &dirs : nullptr, bodies.pos[c.bodyA],
                                                        bodies.pos[c.bodyB], btgAnchoredPair(pa.flags, pb.flags), params));
        if (rolling && (params.solverFlags & BTG_SOLVER_ROLLING_FRICTION))
            rolling->push_back(btgPrepareRolling(&c, a, b, mat, solvable, bodies.rot[c.bodyA], bodies.rot[c.bodyB], pa, pb));
    }
    return edges;
}

}  // namespace btgpu::ref
