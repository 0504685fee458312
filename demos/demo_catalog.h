// demo_catalog.h — the demos btgpu_demos runs, as Bullet's example browser lists them: each a
// scene of tests/scenes/ (shared with the benchmark and the tests), how many steps it runs by
// default and how the camera looks at it.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "scenes/scenes.h"

class btRaycastVehicle;

namespace btgpu::demos {

// One world of a demo: the scene and what the demo drives or draws beside its bodies.
struct DemoWorld {
    scenes::ScenePtr scene;
    btRaycastVehicle* vehicle = nullptr;  // the vehicle demo's, owned by the scene
};

struct Demo {
    std::string name;
    std::string description;
    std::function<DemoWorld(scenes::WorldKind, const Config&)> make;
    int steps = 300;            // default steps of 1/60 s
    bool rays = false;          // casts BenchmarkDemo's 500-ray fan on both worlds each step
    float yawDegrees = 35, pitchDegrees = 25;
    float zoom = 1;             // < 1 moves the camera closer than the framing of the bodies
    bool followFirstBody = false;  // camera target on body 1 (the vehicle's chassis)
};

const std::vector<Demo>& catalog();
const Demo* find(const std::string& name);

}  // namespace btgpu::demos
