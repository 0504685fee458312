/* soft_rows.h — the soft step's rows (SolverKind::SoftStep; Box2D v3's solver, solver.c and
 * contact_solver.c): per step a contact's fixed anchors, masses and restitution speed; per
 * substep its separation followed from the bodies' position and rotation deltas (the
 * narrowphase runs once a step), a soft normal row (spring of contactHertz, damping ratio, push
 * speed), friction on two tangents per point, then restitution once after the substeps (with
 * SoftStepConfig::heldMassRatio a light body under a heavy one held: soft_held_rows.h). Joints
 * keep their Bullet rows (joint_rows.h), solved each substep. Shared by kernels/solve_soft.cl
 * and its CPU reference. */
#ifndef BTG_SOFT_ROWS_H
#define BTG_SOFT_ROWS_H
#include "prelude.h"
#include "types.h"
#include "math.h"
#include "solver_rows.h"
#include "contact_rows.h"
#include "joint_rows.h"
#include "material_rows.h"

/* Box2D's b2Softness: a row of stiffness omega and damping ratio zeta, implicit over a substep.
 * A spring stiffer by r (k and c both times r: omega and zeta times sqrt r) keeps its bias rate
 * and has stiffness r x a2 (massScale = r a2 / (1 + r a2), impulseScale = 1 / (1 + r a2)). */
typedef struct {
    float biasRate;     /* 1/s: velocity bias per metre of penetration */
    float massScale;    /* share of the effective mass the row applies */
    float impulseScale; /* share of the accumulated impulse it relaxes */
    float stiffness;    /* a2 = h omega (2 zeta + h omega) */
} BtgSoftness;

/* Per-step scalars of the soft solve, by value. */
typedef struct {
    BtgSoftness contact;         /* between two dynamic bodies */
    BtgSoftness fixed;           /* against a static, kinematic or sleeping body (twice the frequency) */
    float h;                     /* s: one substep */
    float invH;                  /* 1/s */
    float pushSpeed;             /* m/s: fastest the soft bias pushes a penetration apart (contactSpeed) */
    float restitutionThreshold;  /* m/s: slower approaches do not bounce */
    float warmScale;             /* the cache's impulse (a step's total, times the warm-start factor)
                                    to the first substep's: 1 / (substeps x factor); 0: no warm start */
    float jointBoundScale;       /* 1 / substeps: a joint row's bounds are N s a step */
    int substeps;
    int frictionInSolve;         /* friction rows also in the biased solve, not only in the relax */
    float maxSag;                /* m: a loaded spring stiffens so it sinks no more (SoftStepConfig::maxSag); 0: never */
    float omega2Contact;         /* (rad/s)^2 of the two springs */
    float omega2Fixed;
    float heldMassRatio;         /* SoftStepConfig::heldMassRatio: a pair whose inverse masses differ more holds its light body (0: never) */
    /* What the scalars above derive from, for a step that takes more substeps than the host
     * chose (btgSoftSubstepsFor, btgSoftParamsWith) */
    float dt;                    /* s: the fixed step */
    float hertz;                 /* SoftStepConfig::contactHertz, uncapped */
    float zeta;                  /* SoftStepConfig::dampingRatio */
    float warmstartFactor;       /* btContactSolverInfo::m_warmstartingFactor */
    float rootRatioSubsteps;     /* SoftStepConfig::substepsPerRootMassRatio (0: substeps stay) */
    int maxSubsteps;             /* at most this many however heavy */
    uint orderSeed;              /* SOLVER_RANDMIZE_ORDER: BtgStepParams.randomSeed (0: off): each substep's sweeps
                                    take their colours and points in an order of their own (btgSoftSweepKey) */
    int interleave;              /* SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS: the relax's friction rows
                                    point by point after its normal row */
    int processingThreshold;     /* BTG_SOLVER_PROCESSING_THRESHOLD: a point farther apart than its pair's contact
                                    processing threshold gets no rows and keeps its impulses (as convertContacts) */
    float cfmStiffness;          /* N/m, with cfmDamping N s/m: m_globalCfm's spring for every contact without its own
                                    (btgSoftCfmSpring; 0: none) */
    float cfmDamping;
    int rolling;                 /* BTG_SOLVER_ROLLING_FRICTION: the relax solves the contacts' rolling rows (btgSoftRolling) */
    int anisotropic;             /* BTG_SOLVER_ANISOTROPIC_FRICTION: a contact of an anisotropic body takes Bullet's
                                    directions (BTG_SOFT_BULLET_DIRECTIONS) from prepare_contacts' BtgFrictionDirs
                                    (applyAnisotropicFriction's scaled directions) */
    int twoDirections;           /* SOLVER_USE_2_FRICTION_DIRECTIONS: with Bullet's directions, both rows (else the first
                                    alone, as Bullet's one row) */
    int gather;                  /* every substep's warm start gathered from the bodies' edges (btgSoftGathers: rolling
                                    rows or held pairs); 0: the substeps after the first carry the last one's velocity
                                    change (BTG_SOFT_BODY_CARRY) */
} BtgSoftParams;

/* m_globalCfm as a spring: Bullet solves a contact of raw cfm and erp as the implicit spring of
 * dt k + d = 1 / cfm and erp = dt k / (dt k + d) (setupContactConstraint, which takes exactly
 * that cfm and erp for a contact of stiffness k and damping d), so k = erp / (dt cfm) and
 * d = (1 - erp) / cfm, with its contacts' erp (m_erp2). */
static inline void btgSoftCfmSpring(BtgSoftParams* p, float globalCfm, float erp, float dt)
{
    p->cfmStiffness = 0.0f;
    p->cfmDamping = 0.0f;
    if (!(globalCfm > 0.0f) || !(dt > 0.0f)) return;
    p->cfmStiffness = erp / (dt * globalCfm);
    p->cfmDamping = (1.0f - erp) / globalCfm;
}

/* The order key of a substep's solve (relax 0) or relax (1) sweep (solver_rows.h). */
static inline uint btgSoftSweepKey(BtgSoftParams p, int substep, int relax)
{
    return btgSweepKey(p.orderSeed, substep, relax ? BTG_ORDER_FRICTION : BTG_ORDER_NORMALS);
}

/* One contact manifold as the soft step solves it (Box2D's b2ContactConstraint). The fields
 * every substep's passes read come first, those only prepare, the warm-start gather,
 * restitution and store read last: a pass touches the struct's first cache lines only. In
 * global memory (solve_soft.cl: btgSoftPack) each anchor's w carries the point's normal mass
 * and the tangents are not read back (btgPlaneSpace of the normal gives them again). */
typedef struct {
    BtgFloat4 normal;                 /* unit, from B towards A; w 0 */
    BtgFloat4 rA[BTG_MAX_POINTS];     /* fixed anchors: point on A minus A's centre at the step's start, m */
    BtgFloat4 rB[BTG_MAX_POINTS];
    BtgFloat4 baseSeparation;         /* per point: distance - n.(rA - rB), m; plus n.(pA - pB) now = distance now */
    BtgFloat4 tangent1Mass;
    BtgFloat4 tangent2Mass;
    BtgFloat4 normalImpulse;          /* per point, accumulated this substep (warm-started from the last), N s */
    BtgFloat4 tangent1Impulse;
    BtgFloat4 tangent2Impulse;
    float friction;
    float restitution;
    int bodyA;
    int bodyB;
    int numPoints;
    int flags;                        /* BTG_SOFT_FIXED, BTG_SOFT_BULLET_DIRECTIONS, BTG_SOFT_IMPACT */
    float springStiffness;            /* N/m, with springDamping N s/m: the pair's own contact spring (Bullet's
                                         setContactStiffnessAndDamping), 0: the soft step's (BtgSoftParams) */
    float springDamping;
    BtgFloat4 stiffening;             /* per point: r >= 1, its spring's stiffness and damping factor this step (the solve's) */
    BtgFloat4 totalNormal;            /* per point, applied over the whole step, N s (Bullet's m_appliedImpulse) */
    BtgFloat4 total1;
    BtgFloat4 total2;
    BtgFloat4 relativeVelocity;       /* per point: normal velocity before the step's forces, m/s (restitution) */
    BtgFloat4 normalMass;             /* per point, kg; 0: no rows (in global memory: the anchors' w) */
    BtgFloat4 tangent1;               /* btPlaneSpace1 of the normal: the two friction directions */
    BtgFloat4 tangent2;
    BtgFloat4 pointRestitution;       /* per point: its restitution (the pair's, or a contact callback's) */
} BtgSoftContact;

/* Point k's lever arms, picked by selects rather than an index: a contact's rows run with k known
 * only at run time, and one indexed read of rA/rB keeps the whole 416-byte contact in a GPU's
 * local memory (the H100's soft_resident had a 1,584-byte stack frame, and a 4-point contact's
 * normal rows took about 5,000 cycles: every field a load and a store through it). */
static inline BtgFloat4 btgSoftArmA(const BtgSoftContact* s, int k)
{
    return btgPick4(s->rA, k);
}
static inline BtgFloat4 btgSoftArmB(const BtgSoftContact* s, int k)
{
    return btgPick4(s->rB, k);
}

/* Contacts a work-item solves side by side on a CPU device (soft_wide.h's lanes, float8), and
 * the floats of a contact's lane in a chunk's block (seven of the contact's, sixteen a point's). */
#define BTG_SOFT_WIDE 8
#define BTG_SOFT_WIDE_FIELDS (7 + 16 * BTG_MAX_POINTS)

/* BtgSoftContact.flags. FIXED: solved with BtgSoftParams.fixed (against a static, kinematic or
 * sleeping body). BULLET_DIRECTIONS: the friction rows run along Bullet's directions for each
 * point (anisotropic friction: btgSoftTakesBulletDirections), not the tangents. IMPACT: a FIXED
 * contact whose point approached faster than BTG_SOFT_IMPACT_SPEED at the step's start while it
 * slipped faster than BTG_SOFT_IMPACT_SLIP (btgSoftRelaxRounds). */
#define BTG_SOFT_FIXED 1
#define BTG_SOFT_BULLET_DIRECTIONS 2
#define BTG_SOFT_IMPACT 4

/* An impact's relax: its rows (the normal sweeps, then friction) run BTG_SOFT_IMPACT_ROUNDS times
 * in each relax of the step, not once. One relax puts the friction rows after the normal rows:
 * at an impact their impulse is large (friction x the impact's), and its torque about the
 * centre turns the face into the ground, which the next substep's normal rows answer by pushing
 * the leading points out and lifting the body. A 0.5 m box thrown level at 2 m/s from 1.5 m hopped
 * 0.83 m/s off the ground (restitution 0), kept 0.94 m/s of its 2 where stock and the rigid
 * answer keep 0.71-0.75, spun about its vertical axis at 0.17 rad/s and stopped at x 1.28 m, not
 * 1.10. Three rounds converge that impact (0.7083 m/s, stock's to four digits, no hop, no
 * spin); four leave a margin. Resting contacts (approach below the speed) keep one round: their
 * friction impulses are small, and the next substep's normal rows take the rest. Only against a
 * fixed body (the ground, a wall, a kinematic or sleeping body): between two dynamic bodies the
 * rounds hand one contact's impulse whole to the lighter body before its other contacts answer
 * (a 1,000 kg box dropped 5 cm onto a 1 kg one pressed it 12.7 mm into the ground, 8.8 without).
 * And only where the point slips at the impact (its friction is what the rounds settle): a box
 * landing flat without slip lands as well in one round, and a pile's bodies falling straight down
 * would spend a GPU's whole colour on a few contacts' rounds (the colour waits for its slowest). */
#define BTG_SOFT_IMPACT_SPEED 0.5f
/* A contact's springs sink at most this share of the thinner dynamic body's depth along the
 * normal (and maxSag), but never need to sink less than BTG_SOFT_MIN_SAG (m) (btgSoftPrepare). */
#define BTG_SOFT_SAG_PER_SIZE 0.01f
#define BTG_SOFT_MIN_SAG 1e-5f
#define BTG_SOFT_IMPACT_SLIP 0.1f
#define BTG_SOFT_IMPACT_ROUNDS 4

/* Per body, eight rows of the soft scratch (BTG_SOFT_BODY_ROWS x numBodies). The first four,
 * one 64-byte line, are all a contact's rows read of a body besides its solver record
 * (solve_soft.cl): its velocity during the stage (the device keeps it there and writes it back
 * at the end; w of VEL_LIN the body's solver kind), and the position and rotation moved so far
 * this step (every point's separation applies the rotation as its matrix, made once a side by
 * btgSoftDeltaOf). Then the linear velocity change the step's forces make per substep, and
 * prepare's note of the body's supports (heldMassRatio). */
#define BTG_SOFT_BODY_ROWS 8
#define BTG_SOFT_VEL_LIN 0   /* m/s (the device's; the CPU reference keeps its own velocities) */
#define BTG_SOFT_VEL_ANG 1   /* rad/s */
#define BTG_SOFT_DELTA_POS 2 /* m */
#define BTG_SOFT_DELTA_ROT 3 /* unit quaternion */
#define BTG_SOFT_FORCE_LIN 4 /* m/s per substep */
/* row 5: unused (the forces' angular change is the step's start's: btgSoftBodyBegin) */
#define BTG_SOFT_SUPPORT 6   /* x: its contacts with fixed bodies, y: the last one's index, z: 1 if a pair holds it (floats) */
/* The velocity after this substep's forces, before its warm start (BTG_SOFT_BODY_CARRY's origin):
 * only where the substeps carry their warm start, so the angular half shares the support's row
 * (a held step gathers: BtgSoftParams.gather). */
#define BTG_SOFT_MARK_LIN 7
#define BTG_SOFT_MARK_ANG 6
/* Rows of a body's solver record for the step (the device's: btgMakeSolverBody's fields packed
 * into one 64-byte line, solve_soft.cl's soft_solver_bodies). */
#define BTG_SOFT_SOLVER_ROWS 4

/* What a contact's rows read of a body's motion so far this step. */
typedef struct {
    BtgFloat4 pos; /* BTG_SOFT_DELTA_POS */
    BtgMat3 rot;   /* btgQuatToMat3 of BTG_SOFT_DELTA_ROT */
} BtgSoftDelta;

/* Edge passes and body passes of the soft solve (the warm start is the velocity body pass's:
 * the bodies gather it). */
#define BTG_SOFT_PREPARE 0
#define BTG_SOFT_SOLVE 2
#define BTG_SOFT_RELAX 3
#define BTG_SOFT_RESTITUTION 4
#define BTG_SOFT_STORE 5
#define BTG_SOFT_BODY_BEGIN 0
#define BTG_SOFT_BODY_VELOCITY 1
#define BTG_SOFT_BODY_POSITION 2
#define BTG_SOFT_BODY_END 3 /* the device's: the velocities back into the world's columns */
#define BTG_SOFT_BODY_CARRY 4 /* a substep after the first, warm start carried (btgSoftBodyCarry) */
/* Or'ed into a solve or relax pass of a substep after the first whose warm start was carried:
 * the contact adds that warm start to its step totals itself (btgSoftCarriedTotals), as the
 * gather's owner side does. */
#define BTG_SOFT_WARM_TOTALS 8

#ifndef __OPENCL_C_VERSION__
static_assert(sizeof(BtgSoftness) == 16, "BtgSoftness layout");
static_assert(sizeof(BtgSoftParams) == 140, "BtgSoftParams layout");
static_assert(sizeof(BtgSoftContact) == 16 * (16 + 2 * BTG_MAX_POINTS) + 32, "BtgSoftContact layout");
#endif

/* b2MakeSoft: hertz 0 is a rigid row. */
static inline BtgSoftness btgMakeSoftness(float hertz, float zeta, float h)
{
    BtgSoftness s;
    if (hertz == 0.0f) {
        s.biasRate = 0.0f;
        s.massScale = 1.0f;
        s.impulseScale = 0.0f;
        s.stiffness = 0.0f;
        return s;
    }
    float omega = 2.0f * 3.14159265359f * hertz;
    float a1 = 2.0f * zeta + h * omega;
    float a2 = h * omega * a1;
    float a3 = 1.0f / (1.0f + a2);
    s.biasRate = omega / a1;
    s.massScale = a2 * a3;
    s.impulseScale = a3;
    s.stiffness = a2;
    return s;
}

/* A soft row's shares of a spring of a2 = h omega (2 zeta + h omega) (btgMakeSoftness's, or one
 * stiffened or of the pair's own k and c): the effective mass it applies, the accumulated
 * impulse it gives up. */
static inline void btgSoftScales(float a2, float* massScale, float* impulseScale)
{
    *massScale = a2 / (1.0f + a2);
    *impulseScale = 1.0f / (1.0f + a2);
}

/* A spring of omega^2 and damping ratio zeta stiffened r times: its stiffness times r, its
 * damping times r^1.5 (its damping ratio times r). The stiffening follows the last step's load,
 * a step late: stiffened with the damping alike (its ratio kept), that lag pumped energy into
 * tall stacks (the tower of 30 breathed 17 mm up and down for the 10 s; damped the more, it
 * settles in 2.5-3.4 s). */
static inline BtgSoftness btgSoftStiffened(float r, float omega2, float zeta, float h)
{
    const float omega = sqrt(omega2), hw = h * omega;
    const float a1 = 2.0f * zeta * r * sqrt(r) + hw * r; /* h (c' + h k') / (m h omega) */
    BtgSoftness s;
    s.stiffness = hw * a1;
    s.biasRate = omega * r / a1;
    btgSoftScales(s.stiffness, &s.massScale, &s.impulseScale);
    return s;
}

/* The step's scalars for `substeps` substeps of p.dt (p's settings kept). Box2D caps the
 * spring at an eighth of the substep rate: stiffer than that and one substep cannot follow it. */
static inline BtgSoftParams btgSoftParamsWith(BtgSoftParams p, int substeps)
{
    p.substeps = substeps;
    p.h = p.dt / (float)substeps;
    p.invH = p.h > 0.0f ? 1.0f / p.h : 0.0f;
    const float hertz = btgMin(btgMax(p.hertz, 0.0f), 0.125f * p.invH);
    p.contact = btgMakeSoftness(hertz, p.zeta, p.h);
    p.fixed = btgMakeSoftness(2.0f * hertz, p.zeta, p.h);
    p.warmScale = p.warmstartFactor > 0.0f ? 1.0f / ((float)substeps * p.warmstartFactor) : 0.0f;
    p.jointBoundScale = 1.0f / (float)substeps;
    const float omega = 2.0f * 3.14159265359f * hertz;
    p.omega2Contact = omega * omega;
    p.omega2Fixed = 4.0f * omega * omega;
    return p;
}

/* Heavier over lighter of an edge's two bodies, 1 unless both are dynamic (flags, inverse masses). */
static inline float btgSoftMassRatio(uint flagsA, float invMassA, uint flagsB, float invMassB)
{
    if (!btgIsSolverDynamic(flagsA) || !btgIsSolverDynamic(flagsB) || !(invMassA > 0.0f) || !(invMassB > 0.0f))
        return 1.0f;
    return btgMax(invMassA, invMassB) / btgMin(invMassA, invMassB);
}

/* Substeps for a step whose largest edge mass ratio is `ratio`: p.substeps, raised to the least
 * n with n^2 >= (rootRatioSubsteps)^2 ratio, at most maxSubsteps. Gauss-Seidel hands a heavy
 * body on a light one only the light one's share of each correction: the stack needs about
 * 1.3 sqrt(ratio) substeps to stand (tests/stability/soft_mass_ratio_model.py). Products, not
 * sqrt, so that host and device agree on every n. */
static inline int btgSoftSubstepsFor(BtgSoftParams p, float ratio)
{
    int n = p.substeps;
    if (!(p.rootRatioSubsteps > 0.0f) || !(ratio > 1.0f)) return n;
    const float need = p.rootRatioSubsteps * p.rootRatioSubsteps * ratio;
    while (n < p.maxSubsteps && (float)n * (float)n < need) ++n;
    return n;
}

#include "soft_body_rows.h" /* the passes over the bodies */

/* ---- contacts ---- */

/* The contact's two friction directions: btPlaneSpace1 of its normal. */
static inline void btgSoftTangents(BtgSoftContact* s)
{
    BtgFloat4 t1, t2;
    btgPlaneSpace(s->normal, &t1, &t2);
    s->tangent1 = btgXyz(t1);
    s->tangent2 = btgXyz(t2);
}

/* Point k's two friction directions: the contact's tangents, or (dirs given: a contact with
 * BTG_SOFT_BULLET_DIRECTIONS) Bullet's directions for the point, as prepare_contacts made them
 * for the bullet mode (with anisotropic friction scaled, btgPrepareAnisotropicFriction: neither
 * unit nor in the tangent plane; a row along a scaled direction bounded by friction x the normal
 * impulse holds friction x scale along that axis, as Bullet's row does). */
static inline BtgFloat4 btgSoftDir1(const BtgSoftContact* s, const BtgFrictionDirs* dirs, int k)
{
    return dirs ? btgXyz(btgPick4(dirs->dir1, k)) : s->tangent1;
}
static inline BtgFloat4 btgSoftDir2(const BtgSoftContact* s, const BtgFrictionDirs* dirs, int k)
{
    return dirs ? btgXyz(btgPick4(dirs->dir2, k)) : s->tangent2;
}
/* Whether a contact takes Bullet's directions: one of an anisotropic body (flagsA/B: its
 * bodies' BtgBodyProps flags). Other contacts keep the tangents. */
static inline int btgSoftTakesBulletDirections(uint flagsA, uint flagsB, BtgSoftParams p)
{
    return p.anisotropic && ((flagsA | flagsB) & BTG_BODY_ANISOTROPIC) != 0u;
}

/* PrepareContacts: c as contact_cache built it (anchors from the step's start, distances, its
 * warm-start impulse: the cached step total times the warm-start factor). a0/b0: the bodies'
 * velocities before the step's forces. */
static inline BtgSoftContact btgSoftPrepare(BtgContact c, BtgSolverBody a, BtgSolverBody b, BtgBodyVel a0,
                                            BtgBodyVel b0, BtgFloat4 restitution, int solvable, BtgSoftParams p,
                                            BtgPairMaterial mat, const BtgFrictionDirs* dirs)
{
    BtgSoftContact s;
    s.normal = btgXyz(c.normal);
    btgSoftTangents(&s);
    const BtgFloat4 n = s.normal;
    s.friction = c.friction;
    /* restitution: per point (a contact callback's may differ); s.restitution the first nonzero
     * one (0: the contact never bounces) */
    s.pointRestitution = restitution;
    s.restitution = 0.0f;
    BTG_FOR_POINTS(k, c.numPoints) {
        if (s.restitution == 0.0f) s.restitution = btgLane(restitution, k);
    }
    s.bodyA = c.bodyA;
    s.bodyB = c.bodyB;
    s.numPoints = c.numPoints;
    s.flags = (a.dynamic && b.dynamic ? 0 : BTG_SOFT_FIXED) | (dirs ? BTG_SOFT_BULLET_DIRECTIONS : 0);
    s.springStiffness = 0.0f;
    s.springDamping = 0.0f;
    if (mat.stiffnessDamping) {
        /* the pair's own spring, kept above Bullet's floor (setupContactConstraint's) */
        s.springStiffness = mat.stiffness < BTG_SIMD_EPSILON ? BTG_SIMD_EPSILON : mat.stiffness;
        s.springDamping = mat.damping < BTG_SIMD_EPSILON ? BTG_SIMD_EPSILON : mat.damping;
    } else if (p.cfmStiffness > 0.0f) {
        /* m_globalCfm's, which the pair's own replaces (as in setupContactConstraint) */
        s.springStiffness = p.cfmStiffness;
        s.springDamping = p.cfmDamping < BTG_SIMD_EPSILON ? BTG_SIMD_EPSILON : p.cfmDamping;
    }
    s.baseSeparation = btgZero4();
    s.normalMass = btgZero4();
    s.tangent1Mass = btgZero4();
    s.tangent2Mass = btgZero4();
    s.normalImpulse = btgZero4();
    s.tangent1Impulse = btgZero4();
    s.tangent2Impulse = btgZero4();
    s.totalNormal = btgZero4();
    s.total1 = btgZero4();
    s.total2 = btgZero4();
    s.relativeVelocity = btgZero4();
    s.stiffening = btgMake4(1.0f, 1.0f, 1.0f, 1.0f);
    const float omega2 = (s.flags & BTG_SOFT_FIXED) ? p.omega2Fixed : p.omega2Contact;
    /* How far this contact's springs may sink: maxSag, and for a thin body at most
     * BTG_SOFT_SAG_PER_SIZE of its depth along the normal (its points' farthest from its centre
     * along n: a box's half height on its face, a sphere's or a lying rod's radius; a dynamic
     * side's, the thinner: a fixed body's centre may be anywhere), not below BTG_SOFT_MIN_SAG.
     * A 60 Hz spring alone sinks g / omega^2 under each weight it carries whatever the body's
     * size: three 1 cm boxes stacked sank 0.28 mm into each other (2.8 % of their size). */
    float depthA = 0.0f, depthB = 0.0f;
    BTG_FOR_POINTS(k, c.numPoints) {
        depthA = btgMax(depthA, btgAbs(btgDot3(btgXyz(c.rA[k]), n)));
        depthB = btgMax(depthB, btgAbs(btgDot3(btgXyz(c.rB[k]), n)));
    }
    const float depth = a.dynamic && b.dynamic ? btgMin(depthA, depthB) : (a.dynamic ? depthA : depthB);
    const float sag = btgMin(p.maxSag, btgMax(BTG_SOFT_SAG_PER_SIZE * depth, BTG_SOFT_MIN_SAG));
    /* The friction's warm start across steps (the cache carries it with BTG_SOLVER_WARM_FRICTION),
     * against a fixed body only and along the tangents only (Bullet's directions follow the slip
     * and change from step to step): started at zero each step a box resting on a slope slid in
     * each step's first substep (0.65 mm/s at 0.1 rad), while between two dynamic bodies the last
     * step's friction rocks the exact towers of 20 and 30 (30 cm) and, with heldMassRatio, throws
     * the held pair (SolverFeatures.SoftStepHoldsABoxOnASlope, SolverModes). */
    const float frictionWarm = (s.flags & BTG_SOFT_FIXED) && !dirs && !(p.heldMassRatio > 0.0f) ? p.warmScale : 0.0f;
    BTG_UNROLL
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        s.rA[k] = btgZero4();
        s.rB[k] = btgZero4();
        if (k >= c.numPoints) continue;
        BtgFloat4 rA = btgXyz(c.rA[k]), rB = btgXyz(c.rB[k]);
        s.rA[k] = rA;
        s.rB[k] = rB;
        btgSetLane(&s.baseSeparation, k, btgLane(c.separation, k) - btgDot3(rA - rB, n));
        if (!solvable) continue;
        if (p.processingThreshold && !btgPointProcessed(btgLane(c.separation, k), mat.processingThreshold)) {
            /* not converted: no rows, and the step's totals (what is stored) are the impulses the
             * point had (the cache kept them unscaled) */
            btgSetLane(&s.totalNormal, k, btgLane(c.normalImpulse, k));
            btgSetLane(&s.total1, k, btgLane(c.friction1Impulse, k));
            btgSetLane(&s.total2, k, btgLane(c.friction2Impulse, k));
            continue;
        }
        BtgJacobian jn = btgPointJacobian(n, rA, rB, a, b);
        btgSetLane(&s.normalMass, k, btgPointRowMass(jn, rA, rB, a, b));
        const BtgFloat4 d1 = btgSoftDir1(&s, dirs, k), d2 = btgSoftDir2(&s, dirs, k);
        const BtgJacobian j1 = btgPointJacobian(d1, rA, rB, a, b), j2 = btgPointJacobian(d2, rA, rB, a, b);
        btgSetLane(&s.tangent1Mass, k, btgPointRowMass(j1, rA, rB, a, b));
        /* scaled directions are not orthogonal: a second row would add friction Bullet's one
         * direction does not have (the parallelogram of two bounded rows), so with one
         * direction the second has no row and no impulse */
        const int second = !dirs || p.twoDirections;
        if (second) btgSetLane(&s.tangent2Mass, k, btgPointRowMass(j2, rA, rB, a, b));
        btgSetLane(&s.normalImpulse, k, btgLane(c.normalImpulse, k) * p.warmScale);
        btgSetLane(&s.tangent1Impulse, k, btgLane(c.friction1Impulse, k) * frictionWarm);
        btgSetLane(&s.tangent2Impulse, k, second ? btgLane(c.friction2Impulse, k) * frictionWarm : 0.0f);
        btgSetLane(&s.relativeVelocity, k, btgRowVelocity(jn, a0, b0));
        if ((s.flags & BTG_SOFT_FIXED) && btgLane(s.relativeVelocity, k) < -BTG_SOFT_IMPACT_SPEED) {
            const float v1 = btgRowVelocity(j1, a0, b0), v2 = btgRowVelocity(j2, a0, b0);
            if (v1 * v1 + v2 * v2 > BTG_SOFT_IMPACT_SLIP * BTG_SOFT_IMPACT_SLIP) s.flags |= BTG_SOFT_IMPACT;
        }
        /* A spring of omega relative to the point's effective mass m sinks by
         * lambda / (m h omega^2) under the impulse lambda it carries a substep: a 1,000 kg box
         * on a 1 kg one 28 cm at 30 Hz, the bottom of a tower of 30 2 cm. Stiffened r times
         * (stiffness and damping alike) it sinks r times less: r is set once a step from the
         * load the point carried last step (its warm start), so that it sinks at most maxSag
         * (within the step it stays put: a stiffness following the substeps' impulses rings). */
        float m = btgLane(s.normalMass, k), load = btgLane(s.normalImpulse, k);
        if (p.maxSag > 0.0f && sag > 0.0f && m > 0.0f && s.springStiffness == 0.0f) {
            float r = load / (m * p.h * omega2 * sag);
            btgSetLane(&s.stiffening, k, r > 1.0f ? r : 1.0f);
        }
    }
    /* One factor for all the manifold's points, its most loaded point's: stiffened point by
     * point, every loaded corner sank maxSag whatever its load, so a box had no spring torque
     * against tipping on its face and exact towers rocked (the tower of 20 48-60 mm in 10 s,
     * never settling; with one factor 16 mm, settled in 0.5 s). */
    float r = 1.0f;
    BTG_FOR_POINTS(k, c.numPoints) {
        r = btgMax(r, btgLane(s.stiffening, k));
    }
    s.stiffening = btgMake4(r, r, r, r);
    return s;
}

/* ---- the warm start body by body ----
 * Each substep's warm start is gathered by the bodies (in the pass that adds the forces' share)
 * rather than swept over the colours: one pass instead of a sweep of every color. A body's
 * list holds an entry per edge it is a dynamic side of, in increasing order (so the sums are
 * the same every run): contact e's side (0: A, 1: B) and whether this side adds the contact's
 * warm start to its totals (its first dynamic side: once a contact), or joint j's side. */
#define BTG_SOFT_ENTRY_JOINT 0x80000000u
static inline uint btgSoftContactEntry(int e, int owner, int side)
{
    return ((uint)e << 2) | ((uint)owner << 1) | (uint)side;
}
static inline uint btgSoftJointEntry(int j, int side)
{
    return BTG_SOFT_ENTRY_JOINT | ((uint)j << 2) | (uint)side;
}
/* btgRowApply's half for one body (side 0: A, 1: B): linear the row's direction on A, response
 * that body's angular velocity per N s (already times its angular factor). */
static BTG_ALWAYS_INLINE void btgSoftApplySide(BtgFloat4 linear, BtgFloat4 response, int side, BtgSolverBody body,
                                               BtgBodyVel* v, float impulse)
{
    const BtgFloat4 l = side ? -linear : linear;
    v->lin = v->lin + (l * body.invMassLin) * impulse * body.linFactor;
    v->ang = v->ang + response * (body.angFactor * impulse);
}
/* WarmStart: this substep starts from the last one's impulses, each point's three applied as one
 * impulse vector (the rows' effect is linear in it), on one of the contact's bodies (its totals:
 * btgSoftWarmTotals). */
static BTG_ALWAYS_INLINE void btgSoftWarmStartSide(const BtgSoftContact* s, int side, BtgSolverBody body, BtgBodyVel* v,
                                                   const BtgFrictionDirs* dirs)
{
    BTG_FOR_POINTS(k, s->numPoints) {
        if (btgLane(s->normalMass, k) == 0.0f) continue;
        float ln = btgLane(s->normalImpulse, k), l1 = btgLane(s->tangent1Impulse, k), l2 = btgLane(s->tangent2Impulse, k);
        BtgFloat4 impulse = btgXyz(s->normal * ln + btgSoftDir1(s, dirs, k) * l1 + btgSoftDir2(s, dirs, k) * l2);
        BtgFloat4 angular = side ? -btgCross3(btgSoftArmB(s, k), impulse) : btgCross3(btgSoftArmA(s, k), impulse);
        btgSoftApplySide(impulse, btgMat3MulVec(body.invI, angular) * body.angFactor, side, body, v, 1.0f);
    }
}
/* The contact's own share of a carried warm start (BTG_SOFT_WARM_TOTALS): the last substep's
 * impulses into the step totals, the normal's in the solve, the friction's in the first pass
 * that solves friction (as btgSoftWarmTotals, whose sums these are, in the same order). */
static BTG_ALWAYS_INLINE void btgSoftCarriedTotals(BtgSoftContact* s, int normal, int friction)
{
    BTG_FOR_POINTS(k, s->numPoints) {
        if (btgLane(s->normalMass, k) == 0.0f) continue;
        if (normal) btgSetLane(&s->totalNormal, k, btgLane(s->totalNormal, k) + btgLane(s->normalImpulse, k));
        if (!friction) continue;
        btgSetLane(&s->total1, k, btgLane(s->total1, k) + btgLane(s->tangent1Impulse, k));
        btgSetLane(&s->total2, k, btgLane(s->total2, k) + btgLane(s->tangent2Impulse, k));
    }
}
/* The pass's own mode, and whether it adds a carried warm start to the totals. */
static inline int btgSoftBaseMode(int mode)
{
    return mode & ~BTG_SOFT_WARM_TOTALS;
}
/* Whether every substep gathers its warm start (btgSoftBodyCarry says when it cannot be carried). */
static inline int btgSoftGathers(BtgSoftParams p)
{
    return p.rolling || p.heldMassRatio > 0.0f;
}
/* The body and edge passes of substep s (0: the step's first). */
static inline int btgSoftVelocityMode(BtgSoftParams p, int s)
{
    return s > 0 && !p.gather ? BTG_SOFT_BODY_CARRY : BTG_SOFT_BODY_VELOCITY;
}
static inline int btgSoftSweepMode(BtgSoftParams p, int s, int relax)
{
    return (relax ? BTG_SOFT_RELAX : BTG_SOFT_SOLVE) | (s > 0 && !p.gather ? BTG_SOFT_WARM_TOTALS : 0);
}
/* What a substep's warm start adds to the contact's step totals. */
static BTG_ALWAYS_INLINE void btgSoftWarmTotals(BtgSoftContact* s)
{
    BTG_FOR_POINTS(k, s->numPoints) {
        if (btgLane(s->normalMass, k) == 0.0f) continue;
        btgSetLane(&s->totalNormal, k, btgLane(s->totalNormal, k) + btgLane(s->normalImpulse, k));
        btgSetLane(&s->total1, k, btgLane(s->total1, k) + btgLane(s->tangent1Impulse, k));
        btgSetLane(&s->total2, k, btgLane(s->total2, k) + btgLane(s->tangent2Impulse, k));
    }
}

/* Point k's separation now: its base plus how far the anchors moved apart along the normal
 * (the normal held fixed over the step). dA/dB: the bodies' deltas. */
static inline float btgSoftSeparation(const BtgSoftContact* s, int k, BtgSoftDelta dA, BtgSoftDelta dB)
{
    BtgFloat4 pA = btgXyz(dA.pos) + btgMat3MulVec(dA.rot, btgSoftArmA(s, k));
    BtgFloat4 pB = btgXyz(dB.pos) + btgMat3MulVec(dB.rot, btgSoftArmB(s, k));
    return btgLane(s->baseSeparation, k) + btgDot3(pA - pB, s->normal);
}

/* Solve (useBias 1) or Relax (0): the normal rows (unless bit 0 of normals is clear:
 * btgSoftHeldNormals solved them), soft against penetration while biased, a speculative gap
 * closed in one substep either way; then the friction rows (in the relax, and also in the solve
 * with frictionInSolve). Bit 1 of normals: the contact supports a held body, whose load it takes
 * within the substep, so its springs are stiffened from the impulse they carry now as well. */
/* The contact's spring for the step (its softness stiffened by its one factor, btgSoftPrepare's:
 * every lane of `stiffening` the same), made once a contact rather than once a point: the square
 * roots and divisions of btgSoftStiffened lie on each row's dependent chain (a GPU's latency). */
static BTG_ALWAYS_INLINE BtgSoftness btgSoftSpringOf(const BtgSoftContact* s, float r, BtgSoftParams p)
{
    const int fixed = (s->flags & BTG_SOFT_FIXED) != 0;
    return r > 1.0f ? btgSoftStiffened(r, fixed ? p.omega2Fixed : p.omega2Contact, p.zeta, p.h) : (fixed ? p.fixed : p.contact);
}
static BTG_ALWAYS_INLINE BtgSoftness btgSoftContactSpring(const BtgSoftContact* s, BtgSoftParams p)
{
    return btgSoftSpringOf(s, s->stiffening.x, p);
}
/* A point's bias against the pair's own spring, stiffness k and damping c, on the point's
 * effective mass m: omega^2 = k / m and 2 zeta omega = c / m make Box2D's a2 = h (c + h k) / m
 * and bias rate k / (c + h k) (Bullet's erp / dt for the same k and c); it rests where the
 * point's load is k times its depth, as stock's does. Sets the row's scales. */
static BTG_ALWAYS_INLINE float btgSoftPairSpringBias(const BtgSoftContact* s, float mass, float sep, BtgSoftParams p,
                                                     float* massScale, float* impulseScale)
{
    const float ck = s->springDamping + p.h * s->springStiffness;
    const float a2 = p.h * ck / mass;
    btgSoftScales(a2, massScale, impulseScale);
    const float bias = *massScale * (s->springStiffness / ck) * sep;
    return bias < -p.pushSpeed ? -p.pushSpeed : bias;
}
/* A point's bias against the soft step's spring (stiffened or not), pushing apart at most
 * pushSpeed. Sets the row's scales. */
static BTG_ALWAYS_INLINE float btgSoftSpringBias(BtgSoftness spring, float sep, BtgSoftParams p, float* massScale,
                                                 float* impulseScale)
{
    *massScale = spring.massScale;
    *impulseScale = spring.impulseScale;
    const float bias = *massScale * spring.biasRate * sep;
    return bias < -p.pushSpeed ? -p.pushSpeed : bias;
}
static BTG_ALWAYS_INLINE void btgSoftNormalRow(BtgSoftContact* s, int k, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va,
                                               BtgBodyVel* vb, BtgSoftDelta dA, BtgSoftDelta dB, int useBias, int normals,
                                               BtgSoftParams p, BtgSoftness contactSpring)
{
    float mass = btgLane(s->normalMass, k);
    if (mass == 0.0f) return;
    float sep = btgSoftSeparation(s, k, dA, dB);
    float old = btgLane(s->normalImpulse, k);
    float bias = 0.0f, massScale = 1.0f, impulseScale = 0.0f;
    if (sep > 0.0f) {
        bias = sep * p.invH;
    } else if (useBias && s->springStiffness > 0.0f) {
        bias = btgSoftPairSpringBias(s, mass, sep, p, &massScale, &impulseScale);
    } else if (useBias) {
        BtgSoftness spring = contactSpring;
        if (normals & 2) {
            float r = btgLane(s->stiffening, k);
            const float omega2 = p.omega2Fixed;
            float now = old / (mass * p.h * omega2 * p.maxSag);
            r = now > r ? now : r;
            spring = btgSoftSpringOf(s, r, p);
        }
        bias = btgSoftSpringBias(spring, sep, p, &massScale, &impulseScale);
    }
    BtgJacobian j = btgPointJacobian(s->normal, btgSoftArmA(s, k), btgSoftArmB(s, k), a, b);
    float vn = btgRowVelocity(j, *va, *vb);
    float next = old - mass * (massScale * vn + bias) - impulseScale * old;
    if (!(next > 0.0f)) next = 0.0f;
    btgSetLane(&s->normalImpulse, k, next);
    btgSetLane(&s->totalNormal, k, btgLane(s->totalNormal, k) + (next - old));
    btgRowApply(j, a, b, va, vb, next - old);
}
#include "soft_friction_rows.h"

/* How many times a sweep runs a contact's normal rows (Gauss-Seidel within the contact before
 * its friction rows): twice in the relax where two or more of its points are solved, else once.
 * One pass leaves the points' impulses in the order they were solved: a box landing flat took
 * its first corner's impulse first and spun (3 m drop: 0.59 rad/s, 13 mm of slide, where stock's
 * ten iterations and the physics leave it still). The relax's rows are rigid (no spring), so a
 * second pass only brings them nearer the contact's own solution: 0.014 rad/s, 0.2 mm. The
 * biased solve's soft rows stay one pass (their spring is made for one; a second there did not
 * help the landing), and so does a contact with a spring of its own (contact stiffness and
 * damping, m_globalCfm): the relax holds back its creep to the spring's depth, and a second pass
 * held it back further (the m_globalCfm box 5.5% short of stock's depth after 5 s, not 3%).
 * SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS keeps one pass. */
static BTG_ALWAYS_INLINE int btgSoftNormalSweeps(const BtgSoftContact* s, int useBias)
{
    if (useBias || s->springStiffness > 0.0f) return 1;
    int solved = 0;
    BTG_FOR_POINTS(k, s->numPoints) {
        solved += btgLane(s->normalMass, k) != 0.0f;
    }
    return solved > 1 ? 2 : 1;
}

/* How many times a sweep runs the contact's rows: BTG_SOFT_IMPACT_ROUNDS in the relax of an
 * impact whose normal rows it solves (not those btgSoftHeldNormals took), else once. */
static BTG_ALWAYS_INLINE int btgSoftRelaxRounds(const BtgSoftContact* s, int useBias, int normals)
{
    return !useBias && (normals & 1) && (s->flags & BTG_SOFT_IMPACT) ? BTG_SOFT_IMPACT_ROUNDS : 1;
}

/* The points in the order they are solved: SOLVER_RANDMIZE_ORDER permutes them by pointKey
 * (btgItemKey of the sweep's key and the contact; 0: in order), as the bullet mode's sweeps do. */
static BTG_ALWAYS_INLINE void btgSoftSolveRound(BtgSoftContact* s, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va,
                                                BtgBodyVel* vb, BtgSoftDelta dA, BtgSoftDelta dB, int useBias,
                                                int normals, BtgSoftParams p, uint pointKey,
                                                const BtgFrictionDirs* dirs)
{
    const int n = s->numPoints;
    const int friction = !useBias || p.frictionInSolve;
    BtgSoftness spring = (s->flags & BTG_SOFT_FIXED) ? p.fixed : p.contact;
    if (useBias && (normals & 1) && !(s->springStiffness > 0.0f)) spring = btgSoftContactSpring(s, p);
    /* SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS: each point's friction rows right after
     * its normal row, bounded by the impulse just found (as the bullet mode's interleaved sweep) */
    if (pointKey == 0u) {
        /* in order (the usual case): the points' loops unrolled, each k a constant */
        if (friction && p.interleave) {
            BTG_FOR_POINTS(k, n) {
                if (normals & 1) btgSoftNormalRow(s, k, a, b, va, vb, dA, dB, useBias, normals, p, spring);
                btgSoftFrictionRows(s, k, a, b, va, vb, dirs);
            }
            return;
        }
        if (normals & 1) {
            const int sweeps = btgSoftNormalSweeps(s, useBias);
            for (int pass = 0; pass < sweeps; ++pass) {
                BTG_FOR_POINTS(k, n) {
                    btgSoftNormalRow(s, k, a, b, va, vb, dA, dB, useBias, normals, p, spring);
                }
            }
        }
        if (!friction) return;
        BTG_FOR_POINTS(k, n) {
            btgSoftFrictionRows(s, k, a, b, va, vb, dirs);
        }
        return;
    }
    if (friction && p.interleave) {
        for (int q = 0; q < n; ++q) {
            const int k = btgPermute(pointKey, n, q);
            if (normals & 1) btgSoftNormalRow(s, k, a, b, va, vb, dA, dB, useBias, normals, p, spring);
            btgSoftFrictionRows(s, k, a, b, va, vb, dirs);
        }
        return;
    }
    const int sweeps = (normals & 1) ? btgSoftNormalSweeps(s, useBias) : 0;
    for (int pass = 0; pass < sweeps; ++pass)
        for (int q = 0; q < n; ++q)
            btgSoftNormalRow(s, btgPermute(pointKey, n, q), a, b, va, vb, dA, dB, useBias, normals, p, spring);
    if (!friction) return;
    for (int q = 0; q < n; ++q) btgSoftFrictionRows(s, btgPermute(pointKey, n, q), a, b, va, vb, dirs);
}
static BTG_ALWAYS_INLINE void btgSoftSolve(BtgSoftContact* s, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb,
                                BtgSoftDelta dA, BtgSoftDelta dB, int useBias, int normals,
                                BtgSoftParams p, uint pointKey, const BtgFrictionDirs* dirs)
{
    const int rounds = btgSoftRelaxRounds(s, useBias, normals);
    for (int round = 0; round < rounds; ++round) btgSoftSolveRound(s, a, b, va, vb, dA, dB, useBias, normals, p, pointKey, dirs);
}

/* Rolling and spinning friction (r: prepare_contacts' BtgRollingContact of the contact, the
 * same rows as the bullet mode's): in each relax, after the contact's friction rows, each
 * point's torsional and two rolling rows, their impulses the step's, carried from relax to relax
 * (prepare_contacts starts them at zero each step, as Bullet does: it never warm-starts them),
 * bounded as solveSingleIteration bounds a step's: the coefficient times the point's normal
 * impulse of the step so far, at most the coefficient itself. Until 2026-12-08 each relax
 * started them at zero, bounded by the substep's normal impulse and a substep's share of the
 * coefficient: at an impact, whose normal impulse comes in one substep, that share let a quarter
 * of stock's rolling impulse through (a sphere of rolling friction 1 landing on a 20 degree ramp
 * rolled on 0.43 m where stock's stops within 0.17 m). Returns r with its impulses updated. */
#define BTG_SOFT_ROLLING_ROUNDS 4
static inline BtgRollingContact btgSoftRolling(BtgRollingContact r, const BtgSoftContact* s, BtgSolverBody a,
                                               BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb)
{
    BtgFloat4 normal = s->totalNormal;
    for (int k = 0; k < BTG_MAX_POINTS; ++k)
        if (btgLane(s->normalMass, k) == 0.0f) btgSetLane(&normal, k, 0.0f);
    btgRollingSolve(&r, s->normal, normal, s->numPoints, a, b, va, vb);
    return r;
}

/* ApplyRestitution, after the substeps: a point that approached faster than the threshold and
 * took an impulse leaves at restitution x its approach speed. A contact's points are swept
 * BTG_SOFT_RESTITUTION_SWEEPS times (Box2D sweeps them once): a face landing flat on four points
 * is one impact, and one Gauss–Seidel sweep over its points hands most of it to the first,
 * turning the body (a box bouncing at 0.8 rose to 1.27 m where the rigid answer is 1.37). */
#define BTG_SOFT_RESTITUTION_SWEEPS 4
static inline void btgSoftRestitution(BtgSoftContact* s, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va,
                                      BtgBodyVel* vb, BtgSoftParams p)
{
    if (s->restitution == 0.0f) return;
    for (int sweep = 0; sweep < (s->numPoints > 1 ? BTG_SOFT_RESTITUTION_SWEEPS : 1); ++sweep)
    BTG_FOR_POINTS(k, s->numPoints) {
        float mass = btgLane(s->normalMass, k), rel = btgLane(s->relativeVelocity, k);
        if (mass == 0.0f || rel > -p.restitutionThreshold || btgLane(s->totalNormal, k) == 0.0f) continue;
        BtgJacobian j = btgPointJacobian(s->normal, btgSoftArmA(s, k), btgSoftArmB(s, k), a, b);
        float vn = btgRowVelocity(j, *va, *vb);
        float old = btgLane(s->normalImpulse, k);
        float next = old - mass * (vn + btgLane(s->pointRestitution, k) * rel);
        if (!(next > 0.0f)) next = 0.0f;
        btgSetLane(&s->normalImpulse, k, next);
        btgSetLane(&s->totalNormal, k, btgLane(s->totalNormal, k) + (next - old));
        btgRowApply(j, a, b, va, vb, next - old);
    }
}

/* StoreImpulses into the contact list: the step's totals (what the cache warm-starts the next
 * step from and the app's manifolds report), friction along the two tangents as directions 1
 * and 2 (cos 1, sin 0); with Bullet's directions along those, which prepare_contacts left in
 * the contact as the bullet mode reports them (before the anisotropic scaling). */
static inline void btgSoftStore(BTG_GLOBAL BtgContact* contacts, int i, const BtgSoftContact* s)
{
    contacts[i].normalImpulse = s->totalNormal;
    contacts[i].friction1Impulse = s->total1;
    contacts[i].friction2Impulse = s->total2;
    if (s->flags & BTG_SOFT_BULLET_DIRECTIONS) return;
    contacts[i].tangent1 = s->tangent1;
    contacts[i].tangent2 = s->tangent2;
    contacts[i].frictionCos = btgMake4(1.0f, 1.0f, 1.0f, 1.0f);
    contacts[i].frictionSin = btgZero4();
}

#include "soft_joint_rows.h"

#endif
