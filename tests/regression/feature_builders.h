// feature_builders.h — what the solver-feature tests build their scenes and measure with: a
// builder that changes each world it makes (a btContactSolverInfo setting), how far a body
// travelled, how far body 2 slid down a slope.
#pragma once
#include <functional>

#include "side_by_side.h"

namespace btgpu::test {

// A builder that applies `change` to each world it makes (a btContactSolverInfo setting).
inline SceneBuilder with(const SceneBuilder& make, const std::function<void(Scene&)>& change)
{
    return [make, change](WorldKind kind, const Config& config) {
        ScenePtr scene = make(kind, config);
        change(*scene);
        return scene;
    };
}
inline std::function<void(Scene&)> solverMode(int bits)
{
    return [bits](Scene& s) { s.world().getSolverInfo().m_solverMode |= bits; };
}

inline btVector3 travel(const Scene& s, int body, const btVector3& start)
{
    return s.body(body)->getWorldTransform().getOrigin() - start;
}

// How far `body` (2: anchorSlope's box) moved along the slope's downhill direction (a slope
// tilted `angle` about z).
inline double downhill(const Scene& s, const btVector3& start, btScalar angle, int body = 2)
{
    const btVector3 down = quatRotate(btQuaternion(btVector3(0, 0, 1), angle), btVector3(-1, 0, 0));
    return (s.body(body)->getWorldTransform().getOrigin() - start).dot(down);
}

}  // namespace btgpu::test
