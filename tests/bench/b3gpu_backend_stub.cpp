// b3gpu_backend_stub.cpp — stands in for b3gpu_backend.cpp where Bullet3's OpenCL libraries
// (libbullet-dev's libBullet3OpenCL_clew and friends) are not installed: the b3gpu row says so.
#include "bench_backend.h"

namespace btgpu::bench {

namespace {

class MissingB3gpu : public Backend {
public:
    std::string name() const override { return "b3gpu"; }
    std::string device() const override { return {}; }
    bool setUp(const Scene&, const Options&, std::string* why) override
    {
        *why = "built without Bullet3's OpenCL libraries";
        return false;
    }
    FrameTime step() override { return {}; }
    void poses(std::vector<Pose>&) override {}
    void info(FrameInfo&, bool) override {}
};

}  // namespace

std::unique_ptr<Backend> makeB3gpuBackend() { return std::make_unique<MissingB3gpu>(); }

}  // namespace btgpu::bench
