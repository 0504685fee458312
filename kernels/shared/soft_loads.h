/* soft_loads.h — what solve_soft.cl's passes read and write of the bodies' soft rows and the
 * soft contacts in global memory: each body's solver record and velocity, its deltas, the soft
 * contacts as each pass loads them (shared data through BTG_SHARED and btgLoadShared4, as
 * grid_barrier.h and soft_kernel_args.h say), and a contact's packing. Not a header of its own:
 * solve_soft.cl includes it after its other headers (it uses their types and macros). */
#ifndef BTG_SOFT_LOADS_H
#define BTG_SOFT_LOADS_H

/* Each body's solver record for the step (soft_solver_bodies, launched before the passes):
 * btgMakeSolverBody's fields in four rows, one 64-byte line, (invI row 0, invMass), (invI row 1,
 * linearFactor x), (invI row 2, linearFactor y), (angularFactor, linearFactor z); its kind
 * (dynamic, moving) is w of the body's VEL_LIN soft row. A contact's rows read two lines of a
 * body (this and the soft rows' first) where reading props, the world inertia and the velocity
 * columns took six to eight. */
static float soft_kind_of(int dynamic, int moving)
{
    return (float)(2 * dynamic + moving);
}
static float soft_kind(uint flags)
{
    return soft_kind_of(btgIsSolverDynamic(flags), btgIsSolverMoving(flags));
}
static BtgSolverBody soft_solver_body(__global const BtgFloat4* restrict softSolver, float kind, int i)
{
    const BtgFloat4 r0 = softSolver[BTG_SOFT_SOLVER_ROWS * i], r1 = softSolver[BTG_SOFT_SOLVER_ROWS * i + 1];
    const BtgFloat4 r2 = softSolver[BTG_SOFT_SOLVER_ROWS * i + 2], r3 = softSolver[BTG_SOFT_SOLVER_ROWS * i + 3];
    BtgSolverBody b;
    b.dynamic = kind >= 2.0f;
    b.moving = kind == 1.0f || kind == 3.0f;
    b.pad0 = 0;
    b.invI.r0 = btgXyz(r0);
    b.invI.r1 = btgXyz(r1);
    b.invI.r2 = btgXyz(r2);
    b.invMass = r0.w;
    b.linFactor = btgMake4(r1.w, r2.w, r3.w, 0.0f);
    b.angFactor = btgXyz(r3);
    b.invMassLin = b.linFactor * b.invMass; /* as btgMakeSolverBody */
    return b;
}
/* Body i as the rows see it: its record and velocity (v: its VEL_LIN row, w the kind). */
static BtgSolverBody load_body(__global const BtgFloat4* restrict softSolver, BTG_SHARED __global BtgFloat4* softBodies,
                               int i, BtgBodyVel* v)
{
    const int r = BTG_SOFT_BODY_ROWS * i;
    const BtgFloat4 l = btgLoadShared4(&softBodies[r + BTG_SOFT_VEL_LIN]);
    const BtgSolverBody b = soft_solver_body(softSolver, l.w, i);
    *v = btgMakeBodyVel(b.moving, l, btgLoadShared4(&softBodies[r + BTG_SOFT_VEL_ANG]));
    return b;
}

static int edge_count(__global const uint* restrict counters, int edgeCapacity)
{
    return (int)min(counters[BTG_COUNTER_EDGES], (uint)edgeCapacity);
}
static int contact_edges(__global const uint* restrict counters, int edgeCapacity, int numJoints)
{
    return (int)min(counters[BTG_COUNTER_CONTACTS], (uint)(edgeCapacity - numJoints));
}

/* A body's velocity written back to its soft rows (w of VEL_LIN: its kind). */
static void store_vel(BtgBodyVel v, BtgSolverBody body, BTG_SHARED __global BtgFloat4* softBodies, int i)
{
    const int r = BTG_SOFT_BODY_ROWS * i;
    softBodies[r + BTG_SOFT_VEL_LIN] = btgMake4(v.lin.x, v.lin.y, v.lin.z, soft_kind_of(body.dynamic, body.moving));
    softBodies[r + BTG_SOFT_VEL_ANG] = btgMake4(v.ang.x, v.ang.y, v.ang.z, 0.0f);
}

/* A soft contact as global memory keeps it: each anchor's w the point's normal mass, which
 * the passes read there (load_soft, load_soft_gather) rather than from normalMass, as they take
 * the tangents from the normal (btgSoftTangents): those fields stay where no pass reads them. */
static BtgSoftContact btgSoftPack(BtgSoftContact s)
{
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        s.rA[k].w = btgLane(s.normalMass, k);
        s.rB[k].w = btgLane(s.normalMass, k);
    }
    return s;
}

/* What a contact's rows read of body row r's motion so far (soft_body's position pass wrote it). */
static BtgSoftDelta load_delta(BTG_SHARED __global BtgFloat4* softBodies, int r)
{
    BtgSoftDelta d;
    d.pos = btgLoadShared4(&softBodies[r + BTG_SOFT_DELTA_POS]);
    d.rot = btgQuatToMat3(btgLoadShared4(&softBodies[r + BTG_SOFT_DELTA_ROT]));
    return d;
}

/* The soft contacts as the bodies' warm-start gather shares them across work-groups: each
 * contact's passes stay with one work-item, but the gather reads its impulses from another
 * (and its owner side writes its totals), so those go through BTG_SHARED (volatile on GPUs,
 * whose per-compute-unit caches are not coherent across a grid barrier). */
static BTG_SHARED __global BtgSoftContact* shared_soft(__global const BtgSoftContact* p)
{
    return (BTG_SHARED __global BtgSoftContact*)p;
}

/* What the gather reads of soft contact i: its points' lever arms on `side`, directions, masses
 * and impulses; and, for the side that adds the warm start to the totals, the totals. */
static BtgSoftContact load_soft_gather(__global BtgSoftContact* softContacts, int i, int side, int totals)
{
    BTG_SHARED __global BtgSoftContact* sc = shared_soft(softContacts);
    BtgSoftContact s;
    s.bodyA = 0;
    s.bodyB = 0;
    s.numPoints = btgLoadSharedInt(&sc[i].numPoints);
    s.flags = btgLoadSharedInt(&sc[i].flags);
    s.friction = 0.0f;
    s.restitution = 0.0f;
    s.springStiffness = 0.0f;
    s.springDamping = 0.0f;
    s.normal = btgLoadShared4(&sc[i].normal);
    btgSoftTangents(&s);
    s.normalMass = btgZero4();
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        const BtgFloat4 r = k < s.numPoints ? btgLoadShared4(side == 0 ? &sc[i].rA[k] : &sc[i].rB[k]) : btgZero4();
        s.rA[k] = side == 0 ? btgXyz(r) : btgZero4();
        s.rB[k] = side == 1 ? btgXyz(r) : btgZero4();
        btgSetLane(&s.normalMass, k, r.w);
    }
    s.normalImpulse = btgLoadShared4(&sc[i].normalImpulse);
    s.tangent1Impulse = btgLoadShared4(&sc[i].tangent1Impulse);
    s.tangent2Impulse = btgLoadShared4(&sc[i].tangent2Impulse);
    s.totalNormal = totals ? btgLoadShared4(&sc[i].totalNormal) : btgZero4();
    s.total1 = totals ? btgLoadShared4(&sc[i].total1) : btgZero4();
    s.total2 = totals ? btgLoadShared4(&sc[i].total2) : btgZero4();
    s.tangent1Mass = btgZero4();
    s.tangent2Mass = btgZero4();
    s.baseSeparation = btgZero4();
    s.stiffening = btgZero4();
    s.relativeVelocity = btgZero4();
    s.pointRestitution = btgZero4();
    return s;
}

/* What pass `mode` reads of soft contact i, the rest zero: a pass loads its rows' fields only
 * (a copy of all 416 bytes every pass would read the friction rows in the solve, the
 * separations in the warm start, ...), the lever arms of the contact's points only. */
static BtgSoftContact load_soft(__global const BtgSoftContact* softContacts, int i, int mode, int frictionInSolve)
{
    BtgSoftContact s;
    s.bodyA = softContacts[i].bodyA;
    s.bodyB = softContacts[i].bodyB;
    s.numPoints = softContacts[i].numPoints;
    s.flags = softContacts[i].flags;
    s.friction = softContacts[i].friction;
    s.restitution = softContacts[i].restitution;
    s.springStiffness = softContacts[i].springStiffness;
    s.springDamping = softContacts[i].springDamping;
    s.normal = softContacts[i].normal;
    s.normalMass = btgZero4();
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        /* read whatever the point count: the reads need not wait for it (a GPU's round trip) */
        const BtgFloat4 loadA = softContacts[i].rA[k], loadB = softContacts[i].rB[k];
        const BtgFloat4 rA = k < s.numPoints ? loadA : btgZero4();
        s.rA[k] = btgXyz(rA);
        s.rB[k] = k < s.numPoints ? btgXyz(loadB) : btgZero4();
        btgSetLane(&s.normalMass, k, rA.w);
    }
    /* a held pair writes its support's impulses and totals, the gather's owner side the totals */
    s.normalImpulse = btgLoadShared4(&shared_soft(softContacts)[i].normalImpulse);
    s.totalNormal = btgLoadShared4(&shared_soft(softContacts)[i].totalNormal);
    const int friction = mode == BTG_SOFT_RELAX || (mode == BTG_SOFT_SOLVE && frictionInSolve);
    const int separation = mode == BTG_SOFT_SOLVE || mode == BTG_SOFT_RELAX;
    s.tangent1 = btgZero4();
    s.tangent2 = btgZero4();
    if (friction) btgSoftTangents(&s);
    s.tangent1Mass = friction ? softContacts[i].tangent1Mass : btgZero4();
    s.tangent2Mass = friction ? softContacts[i].tangent2Mass : btgZero4();
    s.tangent1Impulse = friction ? softContacts[i].tangent1Impulse : btgZero4();
    s.tangent2Impulse = friction ? softContacts[i].tangent2Impulse : btgZero4();
    s.total1 = friction ? btgLoadShared4(&shared_soft(softContacts)[i].total1) : btgZero4();
    s.total2 = friction ? btgLoadShared4(&shared_soft(softContacts)[i].total2) : btgZero4();
    s.baseSeparation = separation ? softContacts[i].baseSeparation : btgZero4();
    s.stiffening = separation ? softContacts[i].stiffening : btgZero4();
    s.relativeVelocity = mode == BTG_SOFT_RESTITUTION ? softContacts[i].relativeVelocity : btgZero4();
    s.pointRestitution = mode == BTG_SOFT_RESTITUTION ? softContacts[i].pointRestitution : btgZero4();
    return s;
}

#endif
