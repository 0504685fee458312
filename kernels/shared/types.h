/* types.h — every struct that crosses the host/device boundary, and the flags they carry.
 * Only 4-byte scalars and 16-byte vectors, padding spelled out; host static_asserts in
 * src/world/layout_checks.cpp and the probe kernel (kernels/probe.cl) check the layout on
 * each device. Units are in the field comments. */
#ifndef BTG_TYPES_H
#define BTG_TYPES_H
#include "prelude.h"

/* Body flags (BtgBodyProps.flags). */
#define BTG_BODY_DYNAMIC 1u      /* moved by the solver: finite mass */
#define BTG_BODY_KINEMATIC 2u    /* moved by the app through its motion state; infinite mass */
#define BTG_BODY_STATIC 4u       /* never moves */
#define BTG_BODY_NO_RESPONSE 8u  /* CF_NO_CONTACT_RESPONSE: detected, never solved */
#define BTG_BODY_SLEEPING 16u    /* deactivated: not integrated, not a pair source */
#define BTG_BODY_EXCLUDED 32u    /* bad input or an empty row: takes no part at all */
#define BTG_BODY_GYRO 64u        /* BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY */
#define BTG_BODY_LARGE 128u      /* too big for the uniform grid: tested against every body */
#define BTG_BODY_NEVER_SLEEP 256u /* DISABLE_DEACTIVATION, or a kinematic body */
#define BTG_BODY_CUSTOM_MATERIAL 512u /* CF_CUSTOM_MATERIAL_CALLBACK while gContactAddedCallback is set: its
                                         manifolds go to the host before the solve (contact_callbacks) */
#define BTG_BODY_STIFFNESS_DAMPING 1024u /* CF_HAS_CONTACT_STIFFNESS_DAMPING: soft contacts */
#define BTG_BODY_ANISOTROPIC 2048u        /* CF_ANISOTROPIC_FRICTION: friction directions scaled */
#define BTG_BODY_ANISOTROPIC_ROLLING 4096u /* CF_ANISOTROPIC_ROLLING_FRICTION: rolling axes scaled */
#define BTG_BODY_FRICTION_ANCHOR 8192u    /* CF_HAS_FRICTION_ANCHOR: its pairs' points are friction anchors */
#define BTG_BODY_ADDITIONAL_DAMPING 16384u /* m_additionalDamping: applyDamping's extra damping of slow bodies */
#define BTG_BODY_GYRO_EXPLICIT 32768u     /* BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT (bounded by m_maxGyroscopicForce) */
#define BTG_BODY_GYRO_WORLD 65536u        /* BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_WORLD */
#define BTG_BODY_NO_SHAPE 131072u         /* btEmptyShape: moves and takes joints, never collides (stock's algorithms
                                             for it find no contacts); its row's shape only gives its AABB */

/* Shape kinds (BtgShape.type). Which pairs of them collide, and how, is the pair-kind table
 * (pair_kinds.h), which follows stock's choice of algorithm per pair: BOX is a btBoxShape (a
 * hull row of 8 vertices and 6 faces; box-box pairs are clipped as btBoxBoxDetector does, a box
 * meets every other convex by GJK); HULL is a hull the app gave polyhedral features
 * (initializePolyhedralFeatures: stock clips two of them), and a hull without them is a CONVEX
 * row of its points, collided by GJK as stock does. CONVEX is every convex shape
 * known only by its support function (capsule, cylinder, cone, multi-sphere, convex triangle
 * mesh, uniformly scaled convex): Bullet collides those by GJK/EPA into a persistent manifold
 * (narrowphase_gjk.cl); BtgShape.convexType says which support function. */
#define BTG_SHAPE_SPHERE 0
#define BTG_SHAPE_HULL 1
#define BTG_SHAPE_PLANE 2
#define BTG_SHAPE_CONVEX 3
#define BTG_SHAPE_BOX 4
#define BTG_SHAPE_MESH 5 /* static or kinematic triangle mesh with a BVH (mesh.h) */
#define BTG_SHAPE_HEIGHTFIELD 6 /* static or kinematic height grid (heightfield.h) */
#define BTG_SHAPE_COMPOUND 7 /* btCompoundShape: a range of child collider rows (compound.h); no
                                pair kind takes it, expand_compounds turns its pairs into child pairs */
#define BTG_NUM_SHAPE_KINDS 8

/* Support functions (BtgShape.convexType, shared/support.h). A hull row (BTG_SHAPE_HULL) has
 * BTG_CONVEX_HULL, or BTG_CONVEX_BOX for a btBoxShape, whose GJK core is the box shrunk by its
 * margin (param.w) as Bullet's; the others are BTG_SHAPE_CONVEX rows. */
#define BTG_CONVEX_HULL 0       /* hull vertices, plus margin */
#define BTG_CONVEX_CAPSULE 1    /* param.x radius (= margin), .y half height, m; upAxis */
#define BTG_CONVEX_CYLINDER 2   /* param.xyz half extents without margin, m; upAxis */
#define BTG_CONVEX_CONE 3       /* param.x radius, .y height, m, .z sine of the half angle; upAxis */
#define BTG_CONVEX_SPHERES 4    /* vertex rows: xyz scaled centre, w unscaled radius; param.xyz scaling */
#define BTG_CONVEX_POINTS 5     /* vertex rows: scaled points (convex triangle mesh, scaled hull) */
#define BTG_CONVEX_BOX 6        /* param.xyz half extents with margin, .w margin, m */
#define BTG_CONVEX_SPHERE 7     /* a point core whose margin is the radius (a scaled sphere) */
#define BTG_CONVEX_TRIANGLE 8   /* a mesh triangle as a shape value made per sub-pair, never a table row
                                   (triangle_contacts.h): localAabbMin, localAabbMax, param its three
                                   vertices in the mesh body's frame; margin the concave shape's */
/* BtgShape.convexFlags */
#define BTG_CONVEX_FLAG_CAPSULE 1u      /* a btCapsuleShape (Bullet's closed-form capsule pairs) */
#define BTG_CONVEX_FLAG_SPHERE 2u       /* a btSphereShape (capsule-sphere closed form) */
#define BTG_CONVEX_FLAG_AABB_SUPPORT 4u /* world AABB from the core's support along the world axes
                                           plus the margin (btUniformScalingShape::getAabbSlow) */
#define BTG_CONVEX_FLAG_AABB_SLOW 8u    /* ... from the full support plus the margin
                                           (btConvexInternalShape::getAabbSlow: a cone) */

#define BTG_MAX_POINTS 4 /* contact points per manifold, as Bullet's btPersistentManifold */

/* Static per-body properties; rewritten only when the app changes them. */
typedef struct {
    BtgFloat4 invInertiaLocal; /* 1/(kg m^2) on the principal axes; w: 0 */
    BtgFloat4 linearFactor;    /* per-axis factor (0..1); w: 0 */
    BtgFloat4 angularFactor;   /* per-axis factor (0..1); w: 0 */
    BtgFloat4 gravity;         /* m/s^2, this body's own gravity; w: 0 */
    BtgFloat4 anisotropicFriction; /* per local axis scale of friction directions (BTG_BODY_ANISOTROPIC*); w: 0 */
    float invMass;             /* 1/kg; 0 unless dynamic */
    float friction;            /* coefficient, combined by product (btManifoldResult) */
    float restitution;         /* coefficient, combined by product */
    float linearDamping;       /* Bullet's m_linearDamping: v *= (1 - d)^dt, d in 0..1 */
    float angularDamping;      /* Bullet's m_angularDamping, the same for the angular velocity */
    int shape;                 /* row in the shape table */
    uint flags;                /* BTG_BODY_* */
    int group;                 /* broadphase collision filter group */
    int mask;                  /* broadphase collision filter mask */
    float sleepLinear;         /* m/s: linear sleeping threshold */
    float sleepAngular;        /* rad/s: angular sleeping threshold */
    int proxyOrder;            /* Bullet's broadphase proxy id (m_uniqueId): of two convex bodies the
                                  lower one is their manifold's body 0 (the pair cache's order) */
    float rollingFriction;     /* coefficient (btCollisionObject::m_rollingFriction) */
    float spinningFriction;    /* coefficient (m_spinningFriction) */
    float contactStiffness;    /* N/m (m_contactStiffness; read with BTG_BODY_STIFFNESS_DAMPING) */
    float contactDamping;      /* N s/m (m_contactDamping) */
    /* btRigidBodyConstructionInfo's additional damping (read with BTG_BODY_ADDITIONAL_DAMPING) */
    float additionalDampingFactor;      /* m_additionalDampingFactor */
    float additionalLinearThresholdSqr; /* m_additionalLinearDampingThresholdSqr, (m/s)^2 */
    float additionalAngularThresholdSqr;/* m_additionalAngularDampingThresholdSqr, (rad/s)^2 */
    float contactProcessingThreshold; /* m: m_contactProcessingThreshold (BT_LARGE_FLOAT unless set): a
                                         manifold's points farther apart than the smaller of its two
                                         bodies' stay unsolved (read with BTG_SOLVER_PROCESSING_THRESHOLD) */
} BtgBodyProps;

/* One collision shape; hull data live in the shared vertex/face/index/edge tables. */
typedef struct {
    BtgFloat4 localAabbMin; /* m, margin included */
    BtgFloat4 localAabbMax; /* m, margin included */
    BtgFloat4 param;        /* sphere: x radius m; plane: xyz unit normal, w constant m
                               (points p with n.p = w lie on it); box: xyz half extents, w its
                               Bullet margin (m); hull: unused; convex: per convexType; mesh: xyz the scaling of a
                               btScaledBvhTriangleMeshShape (1 otherwise) */
    int type;               /* BTG_SHAPE_* */
    int firstVertex;        /* hull: rows in the vertex table (BtgFloat4, m, local frame) */
    int numVertices;
    int firstFace;          /* hull: rows in the face table */
    int numFaces;
    int firstEdge;          /* hull: unique edge directions (BtgFloat4, unit, local frame) */
    int numEdges;
    float margin;           /* m: distance added around the hull (0 for boxes, whose margin
                               lies inside the extents as in Bullet); convex: around the core; mesh: its
                               triangles' margin (Bullet's concave getMargin) */
    float breakingThreshold; /* m: Bullet's contact breaking threshold of this shape
                                (getContactBreakingThreshold, or the absolute one); a pair
                                keeps points closer than the smaller of its two shapes' */
    int convexType;         /* BTG_CONVEX_*: the support function (hull and convex rows) */
    int upAxis;             /* capsule, cylinder, cone: 0, 1 or 2 (Bullet's X/Y/Z variants) */
    uint convexFlags;       /* BTG_CONVEX_FLAG_*: what Bullet's shape type decides beyond the
                               support function */
    int mesh;               /* mesh: row in the mesh table (BtgMesh, mesh.h); heightfield: row in
                               the heightfield table (BtgHeightfield, heightfield.h); else -1 */
    int firstChild;         /* compound: its leaves' rows in the child table (BtgChild) ... */
    int numChildren;        /* ... and how many (nested compounds flattened) */
    int pad2;
} BtgShape;

/* One row of a compound's flattened tree (a collider row): a leaf (a convex shape), or a node
 * (a nested compound) that its leaves name as their parent. Stock culls at every level
 * (btCompoundCollisionAlgorithm within btCompoundCollisionAlgorithm), so a leaf pair is kept
 * when every row from the leaf up passes its level's two tests: its box in its holder's frame
 * (the holder's dynamic AABB tree leaf) and its world AABB. */
typedef struct {
    BtgFloat4 pos;          /* m, the row's origin in the body's frame (levels composed); w 0 */
    BtgFloat4 rot;          /* unit quaternion, row to body frame */
    BtgFloat4 treeAabbMin;  /* m, the row's AABB in its holder's frame, as the holder's tree holds it */
    BtgFloat4 treeAabbMax;
    int shape;              /* the row's shape row (a node's: its compound's) */
    int index;              /* the key its manifolds carry (m_index0/1): Bullet's child index for a
                               child of the body's compound; for a leaf of a nested compound its
                               place among the body's leaves (Bullet's own index there, its place
                               in its own compound, is not unique within the body) */
    int useTree;            /* 1: its holder has a dynamic AABB tree (stock queries it first) */
    int parent;             /* the holder's row when a nested compound holds it, else -1 */
} BtgChild;

/* A hull face: its outward plane and its vertex loop (counter-clockwise seen from outside). */
typedef struct {
    BtgFloat4 plane; /* xyz unit outward normal; w = -n.p for points p on the face (m) */
    int firstIndex;  /* rows in the face-index table, which holds vertex numbers of the hull */
    int numIndices;
    int pad0;
    int pad1;
} BtgFace;

/* A candidate pair from the broadphase: body rows, a < b; after expand_compounds a pair of
 * colliders: childA/childB name the compound leaf of each side, 1 + its row in the child table,
 * or BTG_WHOLE_BODY (0, so a zeroed pair is a whole-body pair) for the body's own shape. */
typedef struct {
    int a;
    int b;
    int childA;
    int childB;
} BtgPair;
#define BTG_WHOLE_BODY 0

/* Feature ids (BtgManifoldPoint.featureId): which features of the two shapes made a point, so
 * the warm start can follow it from step to step (box3d's featureId). Unique within a manifold
 * and the same while the same features touch. The top two bits say how the point was made:
 *   SINGLE  the one point of a single-point routine (sphere against anything)
 *   VERTEX  | hull vertex number: hull–plane, the vertex that touches
 *   CLIP    | face of A & 0x7f << 23 | face of B & 0x7f << 16 | edge label << 8 | edge label:
 *           hull–hull face contact, a corner of the clipped polygon named by the two polygon
 *           edges that meet there (box3d's feature pair); a label is BTG_FEATURE_EDGE_OF_B |
 *           edge k of B's face, or edge k of A's face (& 0x7f); whichever hull is the reference,
 *           the same corner gets the same id (the pair is flipped when B is, as box3d does)
 *   EDGES   | edge direction of A & 0x7fff << 15 | of B & 0x7fff: hull–hull edge contact
 * A point against a mesh or heightfield triangle has its triangle's key instead
 * (btgTriangleKey in triangle_contacts.h): Bullet's per-point sub-shape key on the concave side.
 * BTG_FEATURE_UNKNOWN never matches (a point whose features are not known). */
#define BTG_FEATURE_SINGLE 0x00000000u
#define BTG_FEATURE_VERTEX 0x40000000u
#define BTG_FEATURE_CLIP 0x80000000u
#define BTG_FEATURE_EDGES 0xc0000000u
#define BTG_FEATURE_EDGE_OF_B 0x80u
#define BTG_FEATURE_UNKNOWN 0x3fffffffu

/* Sub-shape key of a whole shape (Bullet's m_partId / m_index of a convex shape: -1, -1). */
#define BTG_NO_SUB_SHAPE -1

/* One contact point of a manifold (Bullet's btManifoldPoint). Scalars only (4-byte alignment),
 * so four of them with the manifold's header fill 160 bytes. */
typedef struct {
    float px, py, pz;   /* m: world point on B's surface */
    float distance;     /* m: signed distance along the normal, negative when penetrating; the
                           point on A is p + normal * distance */
    float nx, ny, nz;   /* world unit normal from B towards A (normalWorldOnB) */
    uint featureId;     /* BTG_FEATURE_*: the features that made the point */
} BtgManifoldPoint;

/* The contact of one (sub-shape of A, sub-shape of B): up to 4 points. A manifold is one such
 * pair, so its points share the sub-shape keys (Jolt's SubShapeIDPair per manifold; four copies
 * per point would cost 48 bytes a manifold). A pair owns the range of manifolds its
 * BtgManifoldRange names; today one, at the pair's own slot. */
typedef struct {
    BtgManifoldPoint points[BTG_MAX_POINTS];
    int partIdA;        /* sub-shape key of A: Bullet's m_partId0 (mesh part) ... */
    int indexA;         /* ... and m_index0 (compound child, triangle); BTG_NO_SUB_SHAPE: whole */
    int partIdB;        /* the same of B: m_partId1, m_index1 */
    int indexB;
    int bodyA;
    int bodyB;
    int numPoints;
    float breakingThreshold; /* m: the pair's (btgPairThreshold), as Bullet's manifold keeps its
                                own; the warm-start matching uses it */
} BtgManifold;

/* The manifolds of one pair: manifolds[start, start + count) are those with points (box3d's
 * manifoldStart/manifoldCount). Same index as the pair. */
typedef struct {
    int start;
    int count;
} BtgManifoldRange;

/* The solver rows of one contact manifold (the btSolverConstraint rows Bullet builds from one
 * btPersistentManifold), solved as BtgSolverRow (solver_rows.h). Point k has a normal row along
 * `normal`, a friction row along its own direction 1 (and direction 2 with two friction
 * directions; btgFrictionDir1/2: Bullet sets a lateral friction direction per point) bounded
 * by friction * its normal impulse, and a split-impulse push row along `normal`; all act at
 * its lever arms rA[k], rB[k], and lane k of every per-point field is its rows' state.
 * A solver pass loads only its rows' fields (btgLoadContactRows), which lie in the order the
 * passes read them: a velocity pass reads up to friction1Impulse (friction2Impulse with two
 * friction directions), a push pass up to normalMass and then the push fields, none reads
 * separation; lever arms only of the numPoints points. The warm-start key (the
 * point in A's frame) is not kept here: it is R_A^T rA, and the cache stage recomputes it
 * from rA and A's unchanged rotation when it stores the cache. */
typedef struct {
    int bodyA;
    int bodyB;
    int numPoints;
    float friction;                    /* combined friction coefficient of the pair */
    BtgFloat4 normal;                  /* unit, from B towards A; w: 0 */
    BtgFloat4 rA[BTG_MAX_POINTS];      /* contact point on A minus A's centre, m; w: 0 */
    BtgFloat4 rB[BTG_MAX_POINTS];      /* contact point on B minus B's centre, m; w: 0 */
    BtgFloat4 normalMass;              /* per point: 1 / (J M^-1 J^T) of the normal row, kg; 0: the
                                          point has no rows (its push row shares this mass) */
    BtgFloat4 normalTarget;            /* per point: normal velocity the row drives to, m/s
                                          (restitution, position bias or speculative approach) */
    BtgFloat4 normalImpulse;           /* accumulated per point, N s, in [0, BTG_NORMAL_UPPER_LIMIT] */
    BtgFloat4 tangent1;                /* the normal's tangent plane: unit p and q of btPlaneSpace1 */
    BtgFloat4 tangent2;                /* (q = n x p); w: 0 */
    BtgFloat4 frictionCos;             /* per point: friction direction 1 = cos p + sin q (Bullet's */
    BtgFloat4 frictionSin;             /* m_lateralFrictionDir1); direction 2 = cos q - sin p */
    BtgFloat4 friction1Mass;           /* per point, kg; 0: no row */
    BtgFloat4 friction1Impulse;        /* accumulated along direction 1 per point, N s */
    BtgFloat4 friction2Mass;           /* per point, kg; 0 unless two friction directions */
    BtgFloat4 friction2Impulse;        /* accumulated along direction 2 per point, N s */
    BtgFloat4 pushTarget;              /* per point: split-impulse push velocity, m/s; 0: no push row */
    BtgFloat4 pushImpulse;             /* accumulated split (position) impulse per point, N s */
    BtgFloat4 separation;              /* per point: signed distance, m (negative: penetrating);
                                          what prepare forms the targets from */
    BtgFloat4 normalCfm;               /* per point: the normal and push rows' m_cfm, cfm / dt times
                                          the row mass (m_globalCfm, contact stiffness and damping);
                                          read only with BTG_ROWS_CFM */
} BtgContact;

/* The rolling-friction rows of one contact (convertContact's addTorsionalFrictionConstraint
 * rows; only with BTG_SOLVER_ROLLING_FRICTION, same index as the contact): per point a
 * torsional row about the normal bounded by the spinning friction and two rolling rows about
 * rollAxis1/2 (btPlaneSpace1 of the normal, anisotropic rolling friction applied) bounded by
 * the rolling friction, each times the point's normal impulse and at most the coefficient
 * itself. Angular rows only: their Jacobian and mass are the same at every point of the
 * manifold, the impulses are per point. */
typedef struct {
    BtgFloat4 rollAxis1;     /* unit-ish axis (anisotropy scales it); w: 0 */
    BtgFloat4 rollAxis2;
    BtgFloat4 spinImpulse;   /* accumulated per point, N m s */
    BtgFloat4 roll1Impulse;
    BtgFloat4 roll2Impulse;
    float spinMass;          /* kg m^2: 1 / (n I_A^-1 n + n I_B^-1 n); 0: no row */
    float roll1Mass;         /* 0: no row (no rolling friction, or an axis anisotropy shrank away) */
    float roll2Mass;
    float spinningFriction;  /* combined (btManifoldResult::calculateCombinedSpinningFriction) */
    float rollingFriction;   /* combined rolling friction */
    float pad0;
    float pad1;
    float pad2;
} BtgRollingContact;

/* Each point's friction directions when anisotropic friction scales them
 * (applyAnisotropicFriction: neither unit nor in the tangent plane any more, so not expressible
 * as BtgContact's frictionCos/Sin); only with BTG_SOLVER_ANISOTROPIC_FRICTION, same index as
 * the contact. */
typedef struct {
    BtgFloat4 dir1[BTG_MAX_POINTS]; /* Bullet's m_lateralFrictionDir1 after the scaling; w: 0 */
    BtgFloat4 dir2[BTG_MAX_POINTS]; /* ... Dir2 (read with two friction directions) */
} BtgFrictionDirs;

/* Each point's friction rows' positional targets where its pair's points are friction anchors
 * (setupFrictionConstraint: -(pA - pB).dir m_frictionERP / dt, the anchor's drift along each
 * friction direction); only with BTG_SOLVER_FRICTION_ANCHORS, same index as the contact. */
typedef struct {
    BtgFloat4 target1; /* per point, m/s, along friction direction 1 */
    BtgFloat4 target2; /* ... direction 2 (read with two friction directions) */
} BtgFrictionAnchor;

/* An edge of the constraint graph: one constraint between two bodies. The batching colors
 * edges and the islands walk them, whatever kind of constraint each is: edges [0, contacts)
 * are the contacts, in their order; other kinds (joints) append theirs after them. */
typedef struct {
    int bodyA;
    int bodyB;
} BtgEdge;

/* The warm-start cache: what the next substep's matching and warm start read of one solved
 * contact (btPersistentManifold's cached points), in the contacts' pair order; a pair's
 * manifolds are consecutive entries (Jolt's CachedBodyPair -> CachedManifold). */
typedef struct {
    BtgFloat4 point[BTG_MAX_POINTS]; /* xyz: contact point on A in A's body frame, m (the match
                                        key); w: accumulated normal impulse, N s */
    BtgFloat4 friction1Impulse;      /* accumulated along direction 1 per point, N s (read back with
                                        BTG_SOLVER_WARM_FRICTION) */
    BtgFloat4 friction2Impulse;      /* ... direction 2 */
    uint featureId[BTG_MAX_POINTS];  /* per point, its manifold point's */
    int partIdA;                     /* the manifold's sub-shape keys */
    int indexA;
    int partIdB;
    int indexB;
    int bodyA;
    int bodyB;
    int numPoints;
    int pad0;
} BtgCachedContact;

/* A persistent manifold of a GJK pair (Bullet's btPersistentManifold, narrowphase_gjk.cl): its
 * points in both bodies' frames as they were added, each with the world normal it was found
 * with; refreshed every substep. Kept per pair slot by the narrowphase and per contact (the
 * warm-start cache's order) for the next substep. */
typedef struct {
    BtgFloat4 localA[BTG_MAX_POINTS]; /* m, point on A in A's body frame; w 0 */
    BtgFloat4 localB[BTG_MAX_POINTS]; /* m, point on B in B's body frame; w 0 */
    BtgFloat4 normal[BTG_MAX_POINTS]; /* xyz world unit normal from B towards A (m_normalWorldOnB);
                                         w: distance at the last refresh, m (m_distance1) */
    uint id[BTG_MAX_POINTS];          /* the point's identity, 0..7 (its featureId's low bits) */
    uint subShape[BTG_MAX_POINTS];    /* a convex–concave pair's: the point's triangle key
                                         (btgTriangleKey: Bullet's m_partId/m_index on the concave
                                         side), its manifold point's featureId; else
                                         BTG_FEATURE_UNKNOWN */
    int bodyA;
    int bodyB;
    int numPoints;
    int kind;                         /* BTG_PAIR_* of the pair that wrote it */
    int added;                        /* the identity of the point this substep's collision added
                                         or replaced (the one stock's gContactAddedCallback sees),
                                         -1 for none (the points persisted from earlier substeps),
                                         -2 for several (hulls clipped, boxes: every point) */
    uint addedMask;                   /* bit id set for each point added or replaced this substep */
    uint anchorMask;                  /* bit id set for each point its next refresh keeps as a friction
                                         anchor (store_persistent_manifolds: a body has
                                         CF_HAS_FRICTION_ANCHOR and the last solve left the point's
                                         lateral impulse inside its friction cone) */
    uint addedPoints;                 /* a convex–concave pair's: bit e set for the e-th point of
                                         the pair's manifolds (in their range's order) that this
                                         substep added or replaced (the callbacks' gather reads it:
                                         those points' feature ids are triangle keys, not ids) */
} BtgPersistentManifold;

/* The callbacks' gather (contact_callbacks.cl) names the points a persistent pair added this
 * substep by a mask of their ids (bit featureId & 7); a convex–concave pair's points carry
 * triangle keys instead, so its mask is by their places in the gathered manifold (bit k: point
 * k), flagged with this bit. */
#define BTG_ADDED_BY_POSITION 0x100u

/* Per-step scalars, passed by value to the kernels that need them. */
typedef struct {
    float dt;                    /* s */
    float erp;                   /* btContactSolverInfo::m_erp */
    float erp2;                  /* m_erp2 (split-impulse erp) */
    float splitPenetrationThreshold; /* m_splitImpulsePenetrationThreshold, m (negative) */
    float splitTurnErp;          /* m_splitImpulseTurnErp */
    float warmstartFactor;       /* m_warmstartingFactor (0 when warm starting is off) */
    float restitutionThreshold;  /* m_restitutionVelocityThreshold, m/s */
    float contactThreshold;      /* m: points up to this far apart become contacts */
    float deactivationTime;      /* s: gDeactivationTime; 0 disables sleeping */
    int splitImpulse;            /* m_splitImpulse != 0 */
    int numBodies;
    int twoFrictionDirections;   /* SOLVER_USE_2_FRICTION_DIRECTIONS; else one, along the slip */
    uint solverFlags;            /* BTG_SOLVER_* */
    float sor;                   /* m_sor: relaxation of the contact and friction rows' effective mass;
                                    Bullet's default is 1 (a zeroed BtgStepParams must set it) */
    float globalCfm;             /* m_globalCfm (contacts; the joints take theirs from BtgJointStepParams) */
    int pad0;
    float maxGyroscopicForce;    /* m_maxGyroscopicForce: bounds the explicit gyroscopic term, N m */
    float frictionErp;           /* m_frictionERP: friction anchors' positional error rate */
    uint randomSeed;             /* SOLVER_RANDMIZE_ORDER: this substep's solve-order stream; 0: off */
    int pad1;
} BtgStepParams;
/* BtgStepParams.solverFlags */
#define BTG_SOLVER_VELOCITY_INDEPENDENT_FRICTION 1u /* SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION:
                                                       friction along btPlaneSpace1's axes */
#define BTG_SOLVER_ROLLING_FRICTION 2u /* some body has rolling friction: prepare writes BtgRollingContact rows */
#define BTG_SOLVER_SOFT_CONTACTS 4u    /* some body has contact stiffness and damping */
#define BTG_SOLVER_ANISOTROPIC_FRICTION 8u /* a body has anisotropic friction: prepare writes BtgFrictionDirs */
#define BTG_SOLVER_PROCESSING_THRESHOLD 16u /* a body has a contact processing threshold (setContactProcessingThreshold) */
#define BTG_SOLVER_FRICTION_ANCHORS 32u /* a body has CF_HAS_FRICTION_ANCHOR: prepare writes BtgFrictionAnchor rows */
#define BTG_SOLVER_INTERLEAVE 64u /* SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS: each point's friction
                                     rows right after its normal row */
#define BTG_SOLVER_WARM_FRICTION 128u /* the warm start also takes the friction impulses across steps (the soft
                                         step, whose btgSoftPrepare uses them against fixed bodies along its
                                         tangents, a pure function of the normal that means the same thing next
                                         step; Bullet 3.24 zeroes them at setup, setFrictionConstraintImpulse,
                                         and so does the bullet mode) */

/* Device status flags (one uint, read back with the transforms). */
#define BTG_STATUS_PAIR_OVERFLOW 1u
#define BTG_STATUS_CONTACT_OVERFLOW 2u
#define BTG_STATUS_NAN 4u
#define BTG_STATUS_GRID_BARRIER_TIMEOUT 8u /* a one-launch solve gave up waiting: redo per color */
#define BTG_STATUS_SUB_PAIR_OVERFLOW 16u   /* the midphase found more triangles than subPairs holds */
/* The statuses on which the host redoes the call from its snapshot (poses, velocities, joint
 * state): the stages that keep state across steps (the caches, the deactivation's timers and
 * flags) leave it alone under any of them. */
#define BTG_STATUS_REDO                                                                            \
    (BTG_STATUS_PAIR_OVERFLOW | BTG_STATUS_CONTACT_OVERFLOW | BTG_STATUS_GRID_BARRIER_TIMEOUT |     \
     BTG_STATUS_SUB_PAIR_OVERFLOW)

#ifndef __OPENCL_C_VERSION__
static_assert(sizeof(BtgBodyProps) == 160, "BtgBodyProps layout");
static_assert(sizeof(BtgShape) == 112, "BtgShape layout");
static_assert(sizeof(BtgFace) == 32, "BtgFace layout");
static_assert(sizeof(BtgPair) == 16, "BtgPair layout");
static_assert(sizeof(BtgChild) == 80, "BtgChild layout");
static_assert(sizeof(BtgManifoldPoint) == 32, "BtgManifoldPoint layout");
static_assert(sizeof(BtgManifold) == 32 * BTG_MAX_POINTS + 32, "BtgManifold layout");
static_assert(sizeof(BtgManifoldRange) == 8, "BtgManifoldRange layout");
static_assert(sizeof(BtgContact) == 16 + 16 * 24, "BtgContact layout");
static_assert(sizeof(BtgEdge) == 8, "BtgEdge layout");
static_assert(sizeof(BtgRollingContact) == 16 * 5 + 32, "BtgRollingContact layout");
static_assert(sizeof(BtgFrictionDirs) == 32 * BTG_MAX_POINTS, "BtgFrictionDirs layout");
static_assert(sizeof(BtgFrictionAnchor) == 32, "BtgFrictionAnchor layout");
static_assert(sizeof(BtgCachedContact) == 16 * (BTG_MAX_POINTS + 2) + 4 * BTG_MAX_POINTS + 32,
              "BtgCachedContact layout");
static_assert(sizeof(BtgStepParams) == 80, "BtgStepParams layout");
static_assert(sizeof(BtgPersistentManifold) == 16 * 3 * BTG_MAX_POINTS + 8 * BTG_MAX_POINTS + 32,
              "BtgPersistentManifold layout");
#endif

#endif
