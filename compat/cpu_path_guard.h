// cpu_path_guard.h — bad bodies on the CPU path: named as on the GPU path and kept out of the
// base class's step, so their NaN cannot reach well-formed neighbours. Around one step of
// btDiscreteDynamicsWorld each bad body is held (no pairs, not simulated) and afterwards given
// back its own activation state and filter, so the app's objects end as they were.
#pragma once
#include <functional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <LinearMath/btTransform.h>

#include "btgpu/Report.h"

class btDiscreteDynamicsWorld;
class btCollisionObject;
class btCollisionShape;

namespace btgpu {

class CpuPathGuard {
public:
    // Finds the bad bodies of `world`, reports those that just turned bad, and holds them.
    void hold(btDiscreteDynamicsWorld& world, const std::function<void(Issue)>& report);
    // Gives the held bodies back what hold() changed.
    void release();

private:
    struct Held {
        btCollisionObject* body;
        int activationState;
        int group, mask;
        bool transformSwapped;
        btTransform appTransform;  // the app's own, when swapped
    };
    std::string badShape(const btCollisionShape* shape, int depth);
    static std::string badKinematicMotionState(const btCollisionObject* o);

    std::vector<Held> m_held;
    std::unordered_set<const btCollisionObject*> m_bad;  // bad at the last hold, already named
    std::unordered_map<const btCollisionShape*, std::string> m_shapeVerdicts;  // this hold's
};

}  // namespace btgpu
