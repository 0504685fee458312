// kernel_build_test.cpp — every embedded program builds on this device, so lazy compilation
// (only what the plan needs) never hides a broken kernel. A failure prints the build log.
#include "cl/kernel_source.h"
#include "cl/program.h"
#include "test_device.h"

#include <gtest/gtest.h>

using namespace btgpu;

TEST(KernelBuild, EveryProgramBuilds)
{
    cl::Context& ctx = test::context();
    std::vector<std::string> stems = cl::kernelStems();
    EXPECT_FALSE(stems.empty());
    for (const std::string& stem : stems) {
        try {
            ctx.program(stem);
        } catch (const cl::Error& e) {
            ADD_FAILURE() << e.what();
        }
    }
}
