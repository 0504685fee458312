// test_device.cpp — the shared test context.
#include "test_device.h"

#include <iostream>
#include <memory>

namespace btgpu::test {

cl::Context& context()
{
    static std::unique_ptr<cl::Context> ctx = [] {
        cl::DeviceInfo d = cl::selectDevice("");
        std::cerr << "[btgpu tests] device: " << d.describe() << "\n";
        return std::make_unique<cl::Context>(d);
    }();
    return *ctx;
}

}  // namespace btgpu::test
