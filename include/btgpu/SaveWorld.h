// SaveWorld.h — writes a Bullet world to a `.bullet` file (Bullet's own format: btDefaultSerializer
// and world->serialize()), so that an app can dump the scene it has and run it through
// btgpu_compare (stock Bullet against btgpu). Works on any btCollisionWorld, btgpu's or stock's.
#pragma once
#include <string>

class btCollisionWorld;

namespace btgpu {

struct SaveResult {
    bool ok = false;
    std::string error;  // what went wrong, naming the path; empty when ok
    explicit operator bool() const { return ok; }
};

// Serializes every collision object, rigid body, shape, constraint and the world's gravity and
// solver info as they are now. Never throws; a null world, a path that cannot be written or a
// short write come back as an error.
SaveResult saveWorld(btCollisionWorld* world, const std::string& path);

}  // namespace btgpu
