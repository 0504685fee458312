// cpu_path_rules.cpp — the rules of cpu_path_rules.h, read against Bullet 3.24's sources: a
// setting falls back when btDiscreteDynamicsWorld or btSequentialImpulseConstraintSolver would
// compute something else with it and the GPU path does not follow it. Settings that change
// nothing for a world of rigid bodies without joints stay on the GPU path; each says why below.
#include "cpu_path_rules.h"

#include "joint_rows.h"
#include "subclass_rules.h"

#include "btgpu/Config.h"
#include "parallel_rows.h"
#include "convex_rows.h"
#include "shape_tables.h"
#include "shared/pair_kinds.h"
#include "shared/types.h"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionDispatch/btCompoundCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btConvexPlaneCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/NarrowPhaseCollision/btConvexPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <typeinfo>
#include <vector>
#if defined(__GNUG__)
#include <cxxabi.h>
#endif

namespace btgpu {

namespace {

constexpr int kTypes = MAX_BROADPHASE_COLLISION_TYPES;
using CreateFuncTable = btCollisionAlgorithmCreateFunc* [kTypes][kTypes];
struct DispatcherPeek : btCollisionDispatcher {
    static constexpr CreateFuncTable btCollisionDispatcher::*kContactPoints =
        &DispatcherPeek::m_doubleDispatchContactPoints;
};

std::string typeName(const std::type_info& type)
{
#if defined(__GNUG__)
    int status = 0;
    std::unique_ptr<char, void (*)(void*)> name(abi::__cxa_demangle(type.name(), nullptr, nullptr, &status), std::free);
    if (status == 0 && name) return name.get();
#endif
    return type.name();
}

bool isMeshType(int type)
{
    return type == TRIANGLE_MESH_SHAPE_PROXYTYPE || type == SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE ||
           type == TERRAIN_SHAPE_PROXYTYPE;
}

// The shape types the GPU path simulates (ShapeTables::add; meshes only btBvhTriangleMeshShape
// and its scaled wrapper, which add checks); bit t of a mask is proxy type t.
bool servedShapeType(int type)
{
    return type == BOX_SHAPE_PROXYTYPE || type == CONVEX_HULL_SHAPE_PROXYTYPE ||
           type == CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE || type == SPHERE_SHAPE_PROXYTYPE ||
           type == STATIC_PLANE_PROXYTYPE || isSupportShapeType(type) || isMeshType(type) ||
           type == COMPOUND_SHAPE_PROXYTYPE || type == EMPTY_SHAPE_PROXYTYPE;
}

// Bit t for proxy type t of the shape and, for a compound, of its children (whose pairs run
// through the algorithms registered for their own types).
std::uint64_t shapeTypeBits(const btCollisionShape* shape, int depth = 0)
{
    std::uint64_t bits = std::uint64_t(1) << (shape->getShapeType() & 63);
    if (shape->isCompound() && depth < 8) {
        auto* c = static_cast<const btCompoundShape*>(shape);
        for (int i = 0; i < c->getNumChildShapes(); ++i) bits |= shapeTypeBits(c->getChildShape(i), depth + 1);
    }
    return bits;
}

// The device's shape kinds (BTG_SHAPE_*) a body's shape may take, one bit each: a hull or a
// multi-sphere could be either of two rows (shape_tables.cpp decides), so both bits.
unsigned deviceShapeKinds(const btCollisionShape* shape)
{
    const int type = shape->getShapeType();
    auto bit = [](int kind) { return 1u << kind; };
    if (type == SPHERE_SHAPE_PROXYTYPE) return bit(BTG_SHAPE_SPHERE);
    if (type == MULTI_SPHERE_SHAPE_PROXYTYPE) return bit(BTG_SHAPE_SPHERE) | bit(BTG_SHAPE_CONVEX);
    if (type == BOX_SHAPE_PROXYTYPE) return bit(BTG_SHAPE_BOX) | bit(BTG_SHAPE_HULL);
    if (type == STATIC_PLANE_PROXYTYPE) return bit(BTG_SHAPE_PLANE);
    if (shape->isCompound()) return bit(BTG_SHAPE_COMPOUND);
    if (type == TERRAIN_SHAPE_PROXYTYPE) return bit(BTG_SHAPE_HEIGHTFIELD);
    if (shape->isConcave()) return bit(BTG_SHAPE_MESH);
    if (isSupportShapeType(type)) return bit(BTG_SHAPE_CONVEX);
    return bit(BTG_SHAPE_HULL) | bit(BTG_SHAPE_CONVEX);
}

// Friction anchors need the pair's persistent manifold (the device keeps a point as stock's
// replaceContactPoint does, persistent_manifold.h): "" when every pair kind an anchored body's
// shape may form with a shape in the world keeps one, else the first that does not.
std::string frictionAnchorReason(unsigned anchoredKinds, unsigned worldKinds)
{
    static const char* const kNames[BTG_NUM_SHAPE_KINDS] = {"sphere", "hull", "plane", "convex",
                                                            "box", "mesh", "heightfield", "compound"};
    // A shape that may take two kinds is named by the one listed first (a box as a box).
    static const int kOrder[BTG_NUM_SHAPE_KINDS] = {BTG_SHAPE_BOX,  BTG_SHAPE_SPHERE, BTG_SHAPE_CONVEX,
                                                    BTG_SHAPE_HULL, BTG_SHAPE_PLANE,  BTG_SHAPE_MESH,
                                                    BTG_SHAPE_HEIGHTFIELD, BTG_SHAPE_COMPOUND};
    for (int a : kOrder) {
        if (!((anchoredKinds >> a) & 1u)) continue;
        for (int w : kOrder) {
            if (!((worldKinds >> w) & 1u)) continue;
            const bool compound = a == BTG_SHAPE_COMPOUND || w == BTG_SHAPE_COMPOUND;
            const int kind = btgPairKind(a, w);
            // A convex–concave pair's manifold persists too, but split by normal: its anchors are not kept.
            if (compound || (kind != BTG_PAIR_NONE && (!btgIsPersistentKind(kind) || btgIsConcaveKind(kind))))
                return std::string("friction anchors (CF_HAS_FRICTION_ANCHOR) on a ") + kNames[a] + " beside a " +
                       kNames[w] + " (the device keeps no friction anchor for that pair kind)";
        }
    }
    return "";
}

// What a world built the stock way would use: a btDefaultCollisionConfiguration with the
// default construction info (EPA penetration depth), pools of one element (only its create
// functions are read).
btDefaultCollisionConstructionInfo referenceInfo()
{
    btDefaultCollisionConstructionInfo info;
    info.m_defaultMaxPersistentManifoldPoolSize = 1;
    info.m_defaultMaxCollisionAlgorithmPoolSize = 1;
    return info;
}

btDefaultCollisionConfiguration& referenceConfiguration()
{
    static btDefaultCollisionConfiguration reference(referenceInfo());
    return reference;
}

bool sameCreateFunc(const btCollisionAlgorithmCreateFunc* a, const btCollisionAlgorithmCreateFunc* b)
{
    if (!a || !b) return a == b;
    if (typeid(*a) != typeid(*b) || a->m_swapped != b->m_swapped) return false;
    if (auto* ca = dynamic_cast<const btConvexConvexAlgorithm::CreateFunc*>(a)) {
        auto* cb = static_cast<const btConvexConvexAlgorithm::CreateFunc*>(b);
        if (ca->m_numPerturbationIterations != cb->m_numPerturbationIterations ||
            ca->m_minimumPointsPerturbationThreshold != cb->m_minimumPointsPerturbationThreshold)
            return false;
        if (!ca->m_pdSolver || !cb->m_pdSolver) return ca->m_pdSolver == cb->m_pdSolver;
        return typeid(*ca->m_pdSolver) == typeid(*cb->m_pdSolver);
    }
    if (auto* pa = dynamic_cast<const btConvexPlaneCollisionAlgorithm::CreateFunc*>(a)) {
        auto* pb = static_cast<const btConvexPlaneCollisionAlgorithm::CreateFunc*>(b);
        return pa->m_numPerturbationIterations == pb->m_numPerturbationIterations &&
               pa->m_minimumPointsPerturbationThreshold == pb->m_minimumPointsPerturbationThreshold;
    }
    return true;
}

const char* shapeTypeName(int type)
{
    switch (type) {
        case BOX_SHAPE_PROXYTYPE: return "box";
        case CONVEX_HULL_SHAPE_PROXYTYPE: return "convex hull";
        case CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE: return "convex point cloud";
        case SPHERE_SHAPE_PROXYTYPE: return "sphere";
        case STATIC_PLANE_PROXYTYPE: return "static plane";
        case CAPSULE_SHAPE_PROXYTYPE: return "capsule";
        case CYLINDER_SHAPE_PROXYTYPE: return "cylinder";
        case CONE_SHAPE_PROXYTYPE: return "cone";
        case MULTI_SPHERE_SHAPE_PROXYTYPE: return "multi-sphere";
        case CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE: return "convex triangle mesh";
        case UNIFORM_SCALING_SHAPE_PROXYTYPE: return "uniform scaling";
        case TRIANGLE_MESH_SHAPE_PROXYTYPE: return "triangle mesh";
        case SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE: return "scaled triangle mesh";
        case TERRAIN_SHAPE_PROXYTYPE: return "heightfield";
        case TRIANGLE_SHAPE_PROXYTYPE: return "triangle";
        case COMPOUND_SHAPE_PROXYTYPE: return "compound";
        default: return "shape";
    }
}

// What the GPU path calls each of its shape kinds, in a fallback reason.
const char* shapeKindName(int kind)
{
    switch (kind) {
        case BTG_SHAPE_SPHERE: return "sphere";
        case BTG_SHAPE_HULL: return "convex hull with polyhedral features";
        case BTG_SHAPE_PLANE: return "static plane";
        case BTG_SHAPE_CONVEX:
            return "support-function convex shape (capsule, cylinder, cone, multi-sphere, convex mesh, scaled "
                   "convex, hull without polyhedral features)";
        case BTG_SHAPE_BOX: return "box";
        case BTG_SHAPE_MESH: return "triangle mesh";
        case BTG_SHAPE_HEIGHTFIELD: return "heightfield";
        default: return "shape";
    }
}

}  // namespace

std::string structureReason(const btDiscreteDynamicsWorld& world, ShapeTables* shapes)
{
    std::string joints = jointsStructureReason(world);
    if (!joints.empty()) return joints;
    const btCollisionObjectArray& objs = world.getCollisionObjectArray();
    shapes->beginReferences();
    bool featuredBox = false, plainBox = false;
    int compounds = 0, dynamicCompounds = 0, nestedCompounds = 0;
    unsigned presentKinds = 0, dynamicKinds = 0;  // bit per BTG_SHAPE_*
    for (int i = 0; i < objs.size(); ++i) {
        const btCollisionObject* o = objs[i];
        int type = o->getInternalType();
        // A ghost's overlaps come from Bullet's own broadphase run on the host (ghost_objects.h);
        // on the device one without contact response is a kinematic row that is never solved
        // (its pairs' manifolds, as stock's dispatcher makes them), one with is a collider.
        const bool ghost = type == btCollisionObject::CO_GHOST_OBJECT;
        if (type != btCollisionObject::CO_RIGID_BODY && type != btCollisionObject::CO_COLLISION_OBJECT && !ghost)
            return "collision object " + std::to_string(i) + " is not a rigid body or ghost object (soft or other object)";
        std::string why;
        const int row = shapes->add(o->getCollisionShape(), &why);
        if (row < 0) return "body " + std::to_string(i) + ": " + why;
        if (ghost && !o->hasContactResponse()) continue;  // its shape is never paired on the device
        // A btEmptyShape meets nothing (its row is never paired: BTG_BODY_NO_SHAPE).
        if (o->getCollisionShape()->getShapeType() == EMPTY_SHAPE_PROXYTYPE) continue;
        const BtgShape& shape = shapes->shapes[size_t(row)];
        unsigned kindBit = 1u << shape.type;
        // A compound's pairs are its leaves' (expand_compounds): those kinds must have rows.
        if (shape.type == BTG_SHAPE_COMPOUND) {
            if (!o->isStaticOrKinematicObject() && !ghost) ++dynamicCompounds;
            ++compounds;
            kindBit = 0;
            bool nested = false;
            for (int k = 0; k < shape.numChildren; ++k) {
                const BtgChild& leaf = shapes->children[size_t(shape.firstChild + k)];
                kindBit |= 1u << shapes->shapes[size_t(leaf.shape)].type;
                nested |= leaf.parent >= 0;
            }
            nestedCompounds += nested;
        }
        presentKinds |= kindBit;
        // (a dynamic mesh or heightfield has its own rule, in bodiesReason)
        if (!o->isStaticOrKinematicObject() && !ghost && !(kindBit & (1u << BTG_SHAPE_MESH | 1u << BTG_SHAPE_HEIGHTFIELD)))
            dynamicKinds |= kindBit;
        if (o->getCollisionShape()->getShapeType() == BOX_SHAPE_PROXYTYPE)
            (static_cast<const btBoxShape*>(o->getCollisionShape())->getConvexPolyhedron() ? featuredBox : plainBox) = true;
    }
    // A featured box is served as a featured hull (clipped against featured shapes, GJK against
    // the rest); against a box without features stock still runs btBoxBoxDetector.
    if (featuredBox && plainBox)
        return "boxes with polyhedral features (initializePolyhedralFeatures) beside boxes without";
    // Two compounds meet by btCompoundCompoundCollisionAlgorithm's tree-tree walk, or, where one
    // has no tree (btCompoundShape(false)), by its base class's nested walk: expand_compounds
    // follows both for compounds without nested ones.
    if (dynamicCompounds >= 1 && compounds >= 2 && nestedCompounds > 0)
        return "a compound shape with nested compounds meeting another compound is not on the GPU path yet";
    // Every pair of shape kinds that can meet (a dynamic body against anything) needs a row of
    // the pair-kind table; one without would be a pair the GPU path silently never collides.
    for (int a = 0; a < BTG_NUM_SHAPE_KINDS; ++a)
        for (int b = 0; b < BTG_NUM_SHAPE_KINDS; ++b)
            if ((dynamicKinds >> a & 1u) && (presentKinds >> b & 1u) && btgPairKind(a, b) == BTG_PAIR_NONE)
                return std::string("a ") + shapeKindName(a) + " meeting a " + shapeKindName(b) +
                       " is not on the GPU path yet";
    return "";
}

std::string worldReason(btDiscreteDynamicsWorld& world, const Config& config)
{
    std::string subclass = subclassReason(world);
    if (!subclass.empty()) return subclass;
    // Joints are projected Gauss-Seidel rows solved with the contacts; the Jacobi solver takes
    // contacts only.
    if (world.getNumConstraints() > 0 && config.solver == SolverKind::JacobiMassSplitting)
        return "joints with Config::solver = JacobiMassSplitting (joints are solved by the batched PGS solver only)";
    std::string joints = jointsStepReason(world);
    if (!joints.empty()) return joints;
    // The GPU path is btSequentialImpulseConstraintSolver's projected Gauss-Seidel; any other
    // solver (MLCP, NNCG, the multithreaded one, a subclass) computes something else.
    btConstraintSolver* solver = world.getConstraintSolver();
    if (!solver || typeid(*solver) != typeid(btSequentialImpulseConstraintSolver))
        return "constraint solver " + (solver ? typeName(typeid(*solver)) : std::string("(none)")) +
               " is not exactly btSequentialImpulseConstraintSolver";
    // Pair filtering (needsCollision/needsResponse), the near callback and the algorithms are
    // the dispatcher's; a subclass (btCollisionDispatcherMt among them) may change any of them.
    btDispatcher* dispatcher = world.getDispatcher();
    if (!dispatcher || typeid(*dispatcher) != typeid(btCollisionDispatcher))
        return "collision dispatcher " + (dispatcher ? typeName(typeid(*dispatcher)) : std::string("(none)")) +
               " is not exactly btCollisionDispatcher";
    auto* collisionDispatcher = static_cast<btCollisionDispatcher*>(dispatcher);
    if (collisionDispatcher->getNearCallback() != &btCollisionDispatcher::defaultNearCallback)
        return "custom near callback (btCollisionDispatcher::setNearCallback)";
    // Dispatcher flags stay on the GPU path: CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD (on by
    // default) is served, each shape carrying its own breaking threshold into the pair's
    // (ShapeTables::relativeThreshold); CD_STATIC_STATIC_REPORTED only adds manifolds between
    // static bodies, which the solver skips; the pool flag is memory only.
    btBroadphaseInterface* broadphase = world.getBroadphase();
    const std::type_info& bp = typeid(*broadphase);
    if (bp != typeid(btDbvtBroadphase) && bp != typeid(btAxisSweep3) && bp != typeid(bt32BitAxisSweep3) &&
        bp != typeid(btSimpleBroadphase))
        return "broadphase " + typeName(bp) + " is not one of Bullet's (btDbvtBroadphase, btAxisSweep3, "
                                              "bt32BitAxisSweep3, btSimpleBroadphase)";
    btOverlappingPairCache* pairs = broadphase->getOverlappingPairCache();
    if (!pairs || (typeid(*pairs) != typeid(btHashedOverlappingPairCache) &&
                   typeid(*pairs) != typeid(btSortedOverlappingPairCache)))
        return "overlapping pair cache " + (pairs ? typeName(typeid(*pairs)) : std::string("(none)")) +
               " is not btHashedOverlappingPairCache or btSortedOverlappingPairCache";
    // An overlap filter callback is served: Bullet's broadphase asks it on the host
    // (contact_callbacks.h, which names the case still left to the CPU path).

    // Contact events (started, ended, processed, destroyed) are served: the dispatcher fill's at
    // each internal step and the host's part before the solve (contact_callbacks.h, which names
    // the cases still left to the CPU path).
    // Read by btCompoundCollisionAlgorithm for every child it would collide.
    if (gCompoundChildShapePairCallback) return "gCompoundChildShapePairCallback is set";
    // gContactAddedCallback only runs for bodies with CF_CUSTOM_MATERIAL_CALLBACK: served, as the
    // friction, restitution, rolling and spinning combiners (each point's values computed on the
    // host between the contacts and the solve), but for the cases contact_callbacks.h names.
    // The contact stiffness and damping combiners only run for CF_HAS_CONTACT_STIFFNESS_DAMPING
    // bodies, a body rule.
    // Bullet's breaking threshold is the GPU path's contact threshold: GpuWorld follows a changed
    // gContactBreakingThreshold while Config::contactThreshold is left at its default; the two
    // set to different values fall back.
    if (gContactBreakingThreshold != btScalar(0.02) && gContactBreakingThreshold != config.contactThreshold)
        return "gContactBreakingThreshold changed from 0.02 and Config::contactThreshold set to another value";

    // btContactSolverInfo, against Bullet 3.24's defaults, exactly. m_erp and m_damping are
    // read by the joints (BtgJointStepParams), m_globalCfm by the joints and the contacts'
    // rows, m_sor by the contacts' normal and friction rows (setupContactConstraint's
    // relaxation; the rolling rows and the joints ignore it). Left alone, because
    // btSequentialImpulseConstraintSolver and btDiscreteDynamicsWorld never read them for rigid
    // bodies: m_tau, m_friction, m_restitution,
    // m_maxErrorReduction, m_frictionCFM (manifold points carry their own),
    // m_restingContactRestitutionThreshold ("unused as of 2.81"),
    // m_singleAxisRollingFrictionThreshold, the m_deformable_* fields, m_articulatedWarmstartingFactor,
    // m_jointFeedback*, m_reportSolverAnalytics, m_numNonContactInnerIterations (multibody and
    // soft only). m_frictionERP acts on friction anchors (BtgStepParams.frictionErp) and
    // m_maxGyroscopicForce bounds BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT bodies' term
    // (BtgStepParams.maxGyroscopicForce). m_minimumSolverBatchSize only
    // groups independent islands into one solve, which changes no island's result.
    const btContactSolverInfo& info = world.getSolverInfo();
    static const btContactSolverInfo stock;
    const bool jacobi = config.solver == SolverKind::JacobiMassSplitting;
    if (jacobi && info.m_sor != stock.m_sor)
        return "btContactSolverInfo::m_sor changed from 1 with Config::solver = JacobiMassSplitting";
    if (jacobi && info.m_globalCfm != stock.m_globalCfm)
        return "btContactSolverInfo::m_globalCfm changed from 0 with Config::solver = JacobiMassSplitting";
    if (info.m_linearSlop != stock.m_linearSlop) return "btContactSolverInfo::m_linearSlop changed from 0";
    if (info.m_leastSquaresResidualThreshold != stock.m_leastSquaresResidualThreshold)
        return "btContactSolverInfo::m_leastSquaresResidualThreshold changed from 0 (early solver exit)";
    if (info.m_numIterations < 1)
        return "btContactSolverInfo::m_numIterations below 1 (Bullet then leaves contacts unsolved)";
    // Mode bits: warm starting, two friction directions and velocity-independent friction
    // directions (btPlaneSpace1's, always) are followed; SOLVER_SIMD picks SSE versions of the
    // same row solve; the rest are unread by 3.24's rigid-body solver.
    // SOLVER_ENABLE_FRICTION_DIRECTION_CACHING reuses a point's m_lateralFrictionDir1/2 once
    // BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED is set, and 3.24 sets that flag only with
    // SOLVER_USE_2_FRICTION_DIRECTIONS and SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION
    // both on (convertContact), and then to btPlaneSpace1 of the point's normal. A point the
    // narrowphase refreshes is replaced (replaceContactPoint copies the new point's flags,
    // clearing it); one it keeps keeps its normal too. So the cached directions are the ones
    // convertContact would compute again: caching changes nothing but through anisotropic
    // friction (applied to the cached directions with the body's rotation at the point's first
    // step), which then falls back (bodiesReason). Tested: stock with and without the bit step for
    // step alike (SolverFeatures.FrictionDirectionCachingIsStockNoOp).
    // SOLVER_RANDMIZE_ORDER: stock shuffles its row pools every iteration with its own btRandInt2
    // stream, which the batched solver cannot follow; the PGS solver serves the bit's intent, its
    // solve order (each sweep's colours, each contact's points) permuted every iteration by a
    // stream of its own (solver_rows.h), bitwise the same run to run. The Jacobi solver has no
    // order to permute, the soft step keeps its own (GpuWorld::softStepReason).
    if ((info.m_solverMode & SOLVER_RANDMIZE_ORDER) && jacobi)
        return "btContactSolverInfo::m_solverMode SOLVER_RANDMIZE_ORDER with Config::solver = JacobiMassSplitting";
    // SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS: the PGS solver's velocity iteration is
    // then one sweep, each point's friction rows right after its normal row (BTG_ROWS_INTERLEAVE);
    // the Jacobi solver solves each contact whole, the soft step its friction in the relax
    // (GpuWorld::softStepReason).
    if ((info.m_solverMode & SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS) && jacobi)
        return "btContactSolverInfo::m_solverMode SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS with "
               "Config::solver = JacobiMassSplitting";

    // Dispatch info. m_useContinuous only matters for CCD bodies (a body rule); the CCD fields
    // (m_allowedCcdPenetration) likewise. m_useConvexConservativeDistanceUtil and its threshold
    // are compiled out of 3.24 (USE_SEPDISTANCE_UTIL2), m_useEpa and m_enableSPU are unread,
    // and m_deterministicOverlappingPairs orders stock's pairs (the GPU path is deterministic).
    if (world.getDispatchInfo().m_enableSatConvex)
        return "btDispatcherInfo::m_enableSatConvex (stock then finds the normal of two hulls with polyhedral "
               "features by SAT; the GPU path follows the default, GJK)";
    if (world.getDispatchInfo().m_dispatchFunc != btDispatcherInfo::DISPATCH_DISCRETE)
        return "btDispatcherInfo::m_dispatchFunc is not DISPATCH_DISCRETE (time of impact instead of contacts)";
    return "";
}

BodyRuleContext bodyRuleContext(btDiscreteDynamicsWorld& world)
{
    BodyRuleContext c;
    c.continuous = world.getDispatchInfo().m_useContinuous;
    c.contactAddedCallback = gContactAddedCallback != nullptr;
    c.jacobi = false;
    return c;
}

std::string bodyReason(const btCollisionObject* o, const BodyRuleContext& context)
{
    // Flags left on the GPU path: CF_CHARACTER_OBJECT, CF_DISABLE_VISUALIZE_OBJECT,
    // CF_DISABLE_SPU_COLLISION_PROCESSING, CF_HAS_CUSTOM_DEBUG_RENDERING_COLOR and
    // CF_HAS_COLLISION_SOUND_TRIGGER are unread by 3.24's rigid-body pipeline;
    // CF_CUSTOM_MATERIAL_CALLBACK with gContactAddedCallback is served (contact_callbacks.h, whose
    // unservedReason GpuWorld asks). Collision-check
    // exceptions (setIgnoreCollisionCheck, disableCollisionsBetweenLinkedBodies) are served by
    // filter_pairs.
    const int flags = o->getCollisionFlags();
    if (!servedShapeType(o->getCollisionShape()->getShapeType()))
        return std::string("unsupported shape '") + o->getCollisionShape()->getName() + "'";
    // Contact stiffness and damping give the pair's points setupContactConstraint's erp and cfm
    // (btgPrepareContact), served by the PGS solver.
    if ((flags & btCollisionObject::CF_HAS_CONTACT_STIFFNESS_DAMPING) && context.jacobi)
        return "contact stiffness and damping (CF_HAS_CONTACT_STIFFNESS_DAMPING) with Config::solver = "
               "JacobiMassSplitting";
    // Friction anchors are served where the pair keeps a persistent manifold on the device
    // (bodiesReason takes the pair kinds that do not), by the PGS solver.
    if ((flags & btCollisionObject::CF_HAS_FRICTION_ANCHOR) && context.jacobi)
        return "friction anchors (CF_HAS_FRICTION_ANCHOR) with Config::solver = JacobiMassSplitting";
    // Rolling and spinning friction are BtgRollingContact rows, solved in the PGS solver's
    // rolling sweep; anisotropic rolling friction scales their axes (bodiesReason takes the
    // case of two such bodies).
    if (context.jacobi && (o->getRollingFriction() != btScalar(0) || o->getSpinningFriction() != btScalar(0)))
        return "rolling or spinning friction with Config::solver = JacobiMassSplitting";
    // Anisotropic friction scales the friction directions (BtgFrictionDirs); bodiesReason takes
    // the cases that still fall back.
    if (context.jacobi && o->hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_FRICTION))
        return "anisotropic friction (setAnisotropicFriction) with Config::solver = JacobiMassSplitting";
    // A contact processing threshold leaves a manifold's points farther apart than the smaller of
    // its bodies' unsolved (convertContacts), served by the PGS solver's rows (btgPrepareContact;
    // the soft step's rule is GpuWorld::softStepReason).
    if (context.jacobi && o->getContactProcessingThreshold() < btScalar(BT_LARGE_FLOAT))
        return "contact processing threshold (setContactProcessingThreshold) with Config::solver = JacobiMassSplitting";
    const btRigidBody* rb = btRigidBody::upcast(o);
    // A body made kinematic by its flag alone keeps its mass, and stock's solver moves it by it
    // (initSolverBody reads getInvMass()): what rests on it pushes it back and friction carries
    // less. btgpu takes every kinematic body as infinitely heavy, as Bullet asks kinematic bodies
    // to be (setMassProps(0, ...)): the bullet mode, whose answers are stock's, leaves such a world
    // to stock; the default solver is judged on physics and keeps it.
    if (context.bulletMode && rb && rb->isKinematicObject() && rb->getInvMass() != btScalar(0) &&
        rb->hasContactResponse())
        return "a kinematic body with mass (CF_KINEMATIC_OBJECT without setMassProps(0, ...)) in the bullet mode: "
               "stock's solver moves it by its inverse mass, btgpu's holds kinematic bodies still";
    if (!rb || rb->isStaticOrKinematicObject()) return "";
    if (isMeshType(o->getCollisionShape()->getShapeType()))
        return "dynamic triangle mesh or heightfield body (the GPU path takes static and kinematic ones)";
    // Continuous collision detection (setCcdMotionThreshold) is served step by step: the GPU path
    // where stock's sweeps hit nothing (they then change nothing), the CPU path for a step where
    // one hits (ccd_steps.h; GpuWorld gathers the bodies).
    // All three gyroscopic terms (explicit, implicit world and body frame) are apply_forces'.
    return "";
}

std::string bodiesReason(btDiscreteDynamicsWorld& world, int* bodyIndex, SolverKind solver, unsigned* solverFlags,
                         std::vector<btRigidBody*>* ccdBodies, ShapeWalk* shapes)
{
    *bodyIndex = -1;
    const btCollisionObjectArray& objs = world.getCollisionObjectArray();
    BodyRuleContext context = bodyRuleContext(world);
    const bool jacobi = solver == SolverKind::JacobiMassSplitting;
    context.jacobi = jacobi;
    context.bulletMode = solver == SolverKind::BatchedPgs;
    const size_t n = size_t(objs.size());
    const size_t minPerThread = kBodyRowsPerThread;
    struct Found {
        int index = -1;
        std::string why;
        std::uint64_t shapeTypes = 0;
        unsigned solverFlags = 0;
        int anisotropicRolling = 0;  // bodies with CF_ANISOTROPIC_ROLLING_FRICTION
        int anisotropic = 0;         // bodies with CF_ANISOTROPIC_FRICTION
        int anisotropicOrdered = 0;  // of those (either kind), compound or concave ones
        unsigned anchoredKinds = 0;  // deviceShapeKinds of the CF_HAS_FRICTION_ANCHOR bodies
        unsigned worldKinds = 0;     // ... of every body
        std::vector<btRigidBody*> ccd;  // bodies stock's CCD looks at
        bool swapped = false;           // an object's shape is not shapes->expected's
    };
    std::vector<Found> found(chunkCount(n, minPerThread));
    const std::vector<const btCollisionShape*>* expected =
        shapes && shapes->expected && shapes->expected->size() == n ? shapes->expected : nullptr;
    forEachChunk(n, minPerThread, [&](size_t begin, size_t end, int chunk) {
        Found& f = found[chunk];
        for (size_t i = begin; i < end; ++i) {
            // The fields read below lie on two lines of each object (bytes 184-311 in 3.24's
            // btCollisionObject) and one of its shape, objects scattered over the heap: fetched a
            // few bodies ahead, the loop stops waiting for memory at each body.
            if (i + 8 < end) {
                const char* ahead = reinterpret_cast<const char*>(objs[int(i + 8)]);
                __builtin_prefetch(ahead + 184);
                __builtin_prefetch(ahead + 308);
            }
            if (i + 4 < end) __builtin_prefetch(objs[int(i + 4)]->getCollisionShape());
            const btCollisionObject* o = objs[int(i)];
            if (expected && o->getCollisionShape() != (*expected)[i]) f.swapped = true;
            std::string why = bodyReason(o, context);
            if (!why.empty()) {
                f.index = int(i);
                f.why = std::move(why);
                return;
            }
            f.shapeTypes |= shapeTypeBits(o->getCollisionShape());
            if (o->getRollingFriction() != btScalar(0)) f.solverFlags |= BTG_SOLVER_ROLLING_FRICTION;
            f.anisotropicRolling += o->hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_ROLLING_FRICTION);
            if (o->hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_FRICTION) ||
                o->hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_ROLLING_FRICTION))
                f.anisotropicOrdered += o->getCollisionShape()->isCompound() || o->getCollisionShape()->isConcave();
            if (o->hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_FRICTION)) {
                ++f.anisotropic;
                f.solverFlags |= BTG_SOLVER_ANISOTROPIC_FRICTION;
            }
            if (o->getCollisionFlags() & btCollisionObject::CF_HAS_CONTACT_STIFFNESS_DAMPING)
                f.solverFlags |= BTG_SOLVER_SOFT_CONTACTS;
            if (o->getContactProcessingThreshold() < btScalar(BT_LARGE_FLOAT))
                f.solverFlags |= BTG_SOLVER_PROCESSING_THRESHOLD;
            const unsigned kinds = deviceShapeKinds(o->getCollisionShape());
            f.worldKinds |= kinds;
            if (o->getCollisionFlags() & btCollisionObject::CF_HAS_FRICTION_ANCHOR) {
                f.anchoredKinds |= kinds;
                f.solverFlags |= BTG_SOLVER_FRICTION_ANCHORS;
            }
            // Stock's CCD sweeps only dynamic bodies with a convex shape (a compound has none).
            const btRigidBody* rb = btRigidBody::upcast(o);
            if (ccdBodies && context.continuous && rb && !rb->isStaticOrKinematicObject() &&
                rb->getCcdSquareMotionThreshold() != btScalar(0) && rb->getCollisionShape()->isConvex())
                f.ccd.push_back(const_cast<btRigidBody*>(rb));
        }
    });
    std::uint64_t shapeTypes = 0;
    unsigned flags = 0;
    int anisotropicRolling = 0, anisotropic = 0, anisotropicOrdered = 0;
    unsigned anchoredKinds = 0, worldKinds = 0;
    if (ccdBodies) ccdBodies->clear();
    if (shapes) {
        shapes->complete = true;
        shapes->swapped = shapes->expected && shapes->expected->size() != n;
        for (const Found& f : found) {
            shapes->complete = shapes->complete && f.index < 0;
            shapes->swapped = shapes->swapped || f.swapped;
        }
    }
    for (const Found& f : found) {
        if (f.index >= 0) {
            *bodyIndex = f.index;
            return "body " + std::to_string(f.index) + " (user index " + std::to_string(objs[f.index]->getUserIndex()) +
                   "): " + f.why;
        }
        shapeTypes |= f.shapeTypes;
        flags |= f.solverFlags;
        anisotropicRolling += f.anisotropicRolling;
        anisotropic += f.anisotropic;
        anisotropicOrdered += f.anisotropicOrdered;
        anchoredKinds |= f.anchoredKinds;
        worldKinds |= f.worldKinds;
        if (ccdBodies) ccdBodies->insert(ccdBodies->end(), f.ccd.begin(), f.ccd.end());
    }
    // convertContact scales by body 0's anisotropy, then body 1's: for two convex bodies body 0 is
    // the one of the lower proxy id (the pair cache's order), which the rows carry
    // (BtgBodyProps::proxyOrder); a compound's or a concave body's manifolds are ordered by their
    // algorithms (a child first, the concave side second), which the device does not follow.
    if (anisotropicRolling > 1 && (flags & BTG_SOLVER_ROLLING_FRICTION) && anisotropicOrdered > 0)
        return "anisotropic rolling friction on more than one body, one of them a compound or concave "
               "(CF_ANISOTROPIC_ROLLING_FRICTION: the order Bullet applies two bodies' in is its manifold's body order)";
    if (anisotropic > 1 && anisotropicOrdered > 0)
        return "anisotropic friction on more than one body, one of them a compound or concave (CF_ANISOTROPIC_FRICTION: "
               "the order Bullet applies two bodies' in is its manifold's body order)";
    // With these three bits convertContact keeps a point's directions from its first step,
    // scaled by the body's orientation then (SOLVER_ENABLE_FRICTION_DIRECTION_CACHING, above).
    const int caching = SOLVER_ENABLE_FRICTION_DIRECTION_CACHING | SOLVER_USE_2_FRICTION_DIRECTIONS |
                        SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION;
    if (anisotropic > 0 && (world.getSolverInfo().m_solverMode & caching) == caching)
        return "anisotropic friction with friction direction caching, two friction directions and "
               "velocity-independent directions (the cached directions keep the body's first orientation)";
    if (anchoredKinds) {
        std::string why = frictionAnchorReason(anchoredKinds, worldKinds);
        if (!why.empty()) return why;
    }
    if (solverFlags) *solverFlags = flags;
    return collisionAlgorithmReason(world, shapeTypes);
}

std::string collisionAlgorithmReason(btDiscreteDynamicsWorld& world, std::uint64_t shapeTypes)
{
    auto* dispatcher = dynamic_cast<btCollisionDispatcher*>(world.getDispatcher());
    if (!dispatcher) return "";  // worldReason has already refused it
    const CreateFuncTable& table = dispatcher->*DispatcherPeek::kContactPoints;
    btDefaultCollisionConfiguration& reference = referenceConfiguration();
    // A mesh's triangles meet the convex shapes through the algorithms registered for
    // btTriangleShape (btConvexConcaveCollisionAlgorithm dispatches each triangle): those too.
    if (shapeTypes & ((std::uint64_t(1) << TRIANGLE_MESH_SHAPE_PROXYTYPE) |
                      (std::uint64_t(1) << SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE) | (std::uint64_t(1) << TERRAIN_SHAPE_PROXYTYPE)))
        shapeTypes |= std::uint64_t(1) << TRIANGLE_SHAPE_PROXYTYPE;
    auto checked = [](int t) { return servedShapeType(t) || t == TRIANGLE_SHAPE_PROXYTYPE; };
    for (int a = 0; a < 64; ++a) {
        if (!(shapeTypes >> a & 1) || !checked(a)) continue;
        for (int b = 0; b < 64; ++b) {
            if (!(shapeTypes >> b & 1) || !checked(b)) continue;
            if (!sameCreateFunc(table[a][b], reference.getCollisionAlgorithmCreateFunc(a, b)))
                return std::string("collision algorithm for ") + shapeTypeName(a) + "-" + shapeTypeName(b) +
                       " pairs is not Bullet's default (registerCollisionCreateFunc, "
                       "set{Convex,Plane}ConvexMultipointIterations, or a penetration solver other than EPA)";
        }
    }
    return "";
}

}  // namespace btgpu
