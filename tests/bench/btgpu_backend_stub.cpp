// btgpu_backend_stub.cpp — stands in for btgpu_backend.cpp when the bench is configured with
// BTGPU_BENCH_BTGPU=OFF (the library's world does not link yet): the btgpu row says so.
#include "bench_backend.h"

namespace btgpu::bench {

namespace {

class MissingBtgpu : public Backend {
public:
    std::string name() const override { return "btgpu"; }
    std::string device() const override { return {}; }
    bool setUp(const Scene&, const Options&, std::string* why) override
    {
        *why = "built without the btgpu backend (BTGPU_BENCH_BTGPU=OFF)";
        return false;
    }
    FrameTime step() override { return {}; }
    void poses(std::vector<Pose>&) override {}
    void info(FrameInfo&, bool) override {}
};

}  // namespace

std::unique_ptr<Backend> makeBtgpuBackend() { return std::make_unique<MissingBtgpu>(); }

}  // namespace btgpu::bench
