// save_world.cpp — btgpu::saveWorld: Bullet's serializer into a file, every failure named.
// The file is written to a temporary name beside the target and renamed over it, so a failed
// save never leaves a truncated `.bullet` where a good one was.
#include "btgpu/SaveWorld.h"

#include <btBulletDynamicsCommon.h>
#include <LinearMath/btSerializer.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

namespace btgpu {

static SaveResult failure(const std::string& path, const std::string& what)
{
    SaveResult r;
    r.error = "saveWorld(" + path + "): " + what;
    return r;
}

SaveResult saveWorld(btCollisionWorld* world, const std::string& path)
{
    if (!world) return failure(path, "the world is null");
    if (path.empty()) return failure(path, "the path is empty");
    const unsigned char* bytes = nullptr;
    int size = 0;
    std::unique_ptr<btDefaultSerializer> serializer;
    try {
        serializer = std::make_unique<btDefaultSerializer>();
        world->serialize(serializer.get());
        bytes = serializer->getBufferPointer();
        size = serializer->getCurrentBufferSize();
    } catch (const std::exception& e) {
        return failure(path, std::string("serializing failed: ") + e.what());
    }
    if (!bytes || size <= 0) return failure(path, "Bullet's serializer produced no data");

    const std::string temp = path + ".partial";
    std::FILE* f = std::fopen(temp.c_str(), "wb");
    if (!f) return failure(path, "cannot create " + temp + ": " + std::strerror(errno));
    const size_t written = std::fwrite(bytes, 1, size_t(size), f);
    const int writeErrno = errno;
    const bool closed = std::fclose(f) == 0;
    if (written != size_t(size) || !closed) {
        std::remove(temp.c_str());
        return failure(path, "writing " + std::to_string(size) + " bytes failed after " + std::to_string(written) +
                                 ": " + std::strerror(written != size_t(size) ? writeErrno : errno));
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
        const int e = errno;
        std::remove(temp.c_str());
        return failure(path, std::string("cannot rename the written file into place: ") + std::strerror(e));
    }
    SaveResult ok;
    ok.ok = true;
    return ok;
}

}  // namespace btgpu
