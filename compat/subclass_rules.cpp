// subclass_rules.cpp — which of btDiscreteDynamicsWorld's step hooks a world object overrides.
// A virtual call's target is resolved for the object (GCC's bound member function conversion)
// and compared with the target on a plain btDiscreteDynamicsWorld. Hooks the GPU path does call
// (saveKinematicState, updateAabbs, synchronizeMotionStates, clearForces) are honoured and not
// listed. Without GCC's extension (clang) any subclass falls back.
#include "subclass_rules.h"

#include "btgpu/btGpuDynamicsWorld.h"

#include <typeinfo>

namespace btgpu {

namespace {

// The protected hooks, named through a subclass (pointers to members of btDiscreteDynamicsWorld).
struct Hooks : btDiscreteDynamicsWorld {
    using Step = void (btDiscreteDynamicsWorld::*)(btScalar);
    using Plain = void (btDiscreteDynamicsWorld::*)();
    using Solve = void (btDiscreteDynamicsWorld::*)(btContactSolverInfo&);
    static constexpr Step kInternalStep = &Hooks::internalSingleStepSimulation;
    static constexpr Step kPredict = &Hooks::predictUnconstraintMotion;
    static constexpr Step kIntegrate = &Hooks::integrateTransforms;
    static constexpr Step kActivation = &Hooks::updateActivationState;
    static constexpr Step kPredictive = &Hooks::createPredictiveContacts;
    static constexpr Plain kIslands = &Hooks::calculateSimulationIslands;
    static constexpr Plain kGravity = &Hooks::applyGravity;
    static constexpr Solve kSolve = &Hooks::solveConstraints;
};

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpmf-conversions"
template <class Pmf>
const void* target(btDiscreteDynamicsWorld& w, Pmf pmf)
{
    return reinterpret_cast<const void*>(w.*pmf);
}
const void* collisionTarget(btCollisionWorld& w, void (btCollisionWorld::*pmf)())
{
    return reinterpret_cast<const void*>(w.*pmf);
}
#pragma GCC diagnostic pop

std::string firstOverride(btDiscreteDynamicsWorld& world, btDiscreteDynamicsWorld& plain)
{
    struct Named {
        const char* name;
        bool overridden;
    };
    const Named hooks[] = {
        {"internalSingleStepSimulation", target(world, Hooks::kInternalStep) != target(plain, Hooks::kInternalStep)},
        {"predictUnconstraintMotion", target(world, Hooks::kPredict) != target(plain, Hooks::kPredict)},
        {"integrateTransforms", target(world, Hooks::kIntegrate) != target(plain, Hooks::kIntegrate)},
        {"updateActivationState", target(world, Hooks::kActivation) != target(plain, Hooks::kActivation)},
        {"createPredictiveContacts", target(world, Hooks::kPredictive) != target(plain, Hooks::kPredictive)},
        {"calculateSimulationIslands", target(world, Hooks::kIslands) != target(plain, Hooks::kIslands)},
        {"applyGravity", target(world, Hooks::kGravity) != target(plain, Hooks::kGravity)},
        {"solveConstraints", target(world, Hooks::kSolve) != target(plain, Hooks::kSolve)},
        {"performDiscreteCollisionDetection",
         collisionTarget(world, &btCollisionWorld::performDiscreteCollisionDetection) !=
             collisionTarget(plain, &btCollisionWorld::performDiscreteCollisionDetection)},
        {"computeOverlappingPairs", collisionTarget(world, &btCollisionWorld::computeOverlappingPairs) !=
                                        collisionTarget(plain, &btCollisionWorld::computeOverlappingPairs)},
    };
    for (const Named& h : hooks)
        if (h.overridden) return h.name;
    return "";
}
#endif

}  // namespace

std::string subclassReason(btDiscreteDynamicsWorld& world)
{
    if (typeid(world) == typeid(btGpuDynamicsWorld)) return "";
#if defined(__GNUC__) && !defined(__clang__)
    // A plain world to resolve the hooks on (constructed on nothing: it is never stepped).
    static btDiscreteDynamicsWorld plain(nullptr, nullptr, nullptr, nullptr);
    std::string hook = firstOverride(world, plain);
    if (hook.empty()) return "";
    return "the world's class overrides btDiscreteDynamicsWorld::" + hook + ", which the GPU path does not call";
#else
    return std::string("the world is a subclass of btGpuDynamicsWorld (") + typeid(world).name() +
           "), whose step hooks this compiler cannot inspect";
#endif
}

}  // namespace btgpu
