// cpu_path_rules.h — what sends a btGpuDynamicsWorld to Bullet's CPU path: every Bullet feature
// or setting the GPU path does not follow, found before a step commits to the device. Each rule
// returns "" or a reason naming the feature (and the body, for per-body rules); a silently
// different answer is worse than a slow one. What was left on the GPU path, and why, is said
// next to the rules in cpu_path_rules.cpp.
#pragma once
#include "btgpu/Config.h"

#include <cstdint>
#include <string>
#include <vector>

class btCollisionObject;
class btCollisionShape;
class btDiscreteDynamicsWorld;
class btRigidBody;

namespace btgpu {

struct Config;
struct ShapeTables;

// The scene's make-up: constraints, object kinds, shapes, and body settings fixed at
// construction. Only changes when something is added or removed, so it is checked then.
// Adds every body's shape to the GPU shape tables *shapes on the way, counting references
// (a shape kind they cannot take is a reason).
std::string structureReason(const btDiscreteDynamicsWorld& world, ShapeTables* shapes);

// World-level settings an app may change between any two steps (solver, dispatcher and pair
// cache types, global callbacks and thresholds, btContactSolverInfo, dispatch info): a handful
// of comparisons, checked before every step.
std::string worldReason(btDiscreteDynamicsWorld& world, const Config& config);

// What the per-body rules need from the world, read once per step.
struct BodyRuleContext {
    bool continuous = true;            // getDispatchInfo().m_useContinuous: CCD bodies sweep
    bool contactAddedCallback = false;  // gContactAddedCallback is set
    bool jacobi = false;               // Config::solver is JacobiMassSplitting (its rows are plainer)
    bool bulletMode = false;           // Config::solver is BatchedPgs (the bullet mode: stock's answers)
};
BodyRuleContext bodyRuleContext(btDiscreteDynamicsWorld& world);

// One body's settings that an app may change between steps (flags, friction kinds,
// thresholds, CCD); "" when the GPU path serves the body as it is.
std::string bodyReason(const btCollisionObject* body, const BodyRuleContext& context);

// Every body of the world (in parallel chunks), then the dispatcher's collision algorithms for
// the shape pairs present. Returns the first reason in body order as "body i (user index u):
// …" and sets *bodyIndex to i (-1 for a reason that is not one body's). jacobi: the Jacobi
// solver is configured. *solverFlags (when given, and the bodies are served) gets the
// BTG_SOLVER_* bits the bodies call for (rolling friction, soft contacts). *ccdBodies (when
// given) gets the bodies stock's continuous collision detection looks at (ccd_steps.h).
// *shapes (when given): on the same walk each object's shape against shapes->expected (the
// GPU world's shapesSwapped question, asked where the walk reads that line anyway): swapped when
// one differs or the count does; complete when the walk saw every object (no reason stopped it).
struct ShapeWalk {
    const std::vector<const btCollisionShape*>* expected = nullptr;
    bool complete = false;
    bool swapped = false;
};
std::string bodiesReason(btDiscreteDynamicsWorld& world, int* bodyIndex, SolverKind solver = SolverKind::Auto,
                         unsigned* solverFlags = nullptr, std::vector<btRigidBody*>* ccdBodies = nullptr,
                         ShapeWalk* shapes = nullptr);

// The dispatcher's collision algorithm for each pair of the shape types in `shapeTypes` (bit t:
// proxy type t present) against a stock btDefaultCollisionConfiguration's: catches
// registerCollisionCreateFunc, set{Convex,Plane}ConvexMultipointIterations and a penetration
// depth solver other than EPA.
std::string collisionAlgorithmReason(btDiscreteDynamicsWorld& world, std::uint64_t shapeTypes);

}  // namespace btgpu
