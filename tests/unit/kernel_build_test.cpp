// kernel_build_test.cpp — every embedded program builds on this device, so lazy compilation
// (only what the plan needs) never hides a broken kernel. A failure prints the build log.
#include "cl/buffer.h"
#include "cl/kernel_source.h"
#include "cl/launch.h"
#include "cl/program.h"
#include "shared/types.h"
#include "test_device.h"

#include <cstring>
#include <gtest/gtest.h>
#include <memory>

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

// OpenCL C 1.2 has no variadic macros: PoCL (CI's device) takes them, NVIDIA's compiler refuses the
// program ("variadic macros not supported in OpenCL"), so every GPU world with that program fails.
// A collide kernel's macro once had one; no program text may.
TEST(KernelBuild, NoProgramUsesAVariadicMacro)
{
    for (const std::string& stem : cl::kernelStems()) {
        const std::string text = cl::kernelSource(stem);
        EXPECT_EQ(text.find("__VA_ARGS__"), std::string::npos) << stem;
        // a macro's parameter list with "...": a #define line whose "(...)" or ", ...)" comes
        // before its first space after the name
        for (size_t at = text.find("#define"); at != std::string::npos; at = text.find("#define", at + 1)) {
            const size_t end = text.find('\n', at);
            const std::string line = text.substr(at, end == std::string::npos ? std::string::npos : end - at);
            const size_t name = line.find_first_not_of(' ', 7), open = line.find('(', name);
            const size_t space = line.find(' ', name);
            if (open == std::string::npos || (space != std::string::npos && space < open)) continue;  // no parameters
            const size_t close = line.find(')', open);
            EXPECT_EQ(line.substr(open, close - open).find("..."), std::string::npos) << stem << ": " << line;
        }
    }
}

// A program this process built once is built again from its binary in a later context on the
// same device (each world has a context of its own), and its kernels compute bit for bit what
// the first context's do: the damping of predict_motion (pow) on the same velocities.
TEST(KernelBuild, ALaterContextBuildsFromTheBinaryAndComputesTheSame)
{
    const cl::DeviceInfo& device = test::context().device();
    const int n = 64;
    std::vector<BtgBodyProps> props(n);
    std::vector<BtgFloat4> lin(n), ang(n);
    for (int i = 0; i < n; ++i) {
        props[i] = BtgBodyProps{};
        props[i].flags = BTG_BODY_DYNAMIC;
        props[i].linearDamping = 0.01f * float(i % 17);
        props[i].angularDamping = 0.02f * float(i % 13);
        lin[i] = BtgFloat4{0.3f * float(i) - 7.0f, 1.25f, -0.5f * float(i % 9), 0.0f};
        ang[i] = BtgFloat4{0.1f * float(i % 5), -2.0f + 0.07f * float(i), 3.0f, 0.0f};
    }
    auto damped = [&](cl::Context& ctx, std::vector<BtgFloat4>* outLin, std::vector<BtgFloat4>* outAng) {
        cl::DeviceArray<BtgBodyProps> p;
        cl::DeviceArray<BtgFloat4> l, a;
        p.upload(ctx, props);
        l.upload(ctx, lin);
        a.upload(ctx, ang);
        cl::Launch(ctx, ctx.program("integrate").kernel("predict_motion")).arg(n).arg(p).arg(l).arg(a).arg(1.0f / 60.0f).run(size_t(n));
        *outLin = l.download(ctx, size_t(n));
        *outAng = a.download(ctx, size_t(n));
    };
    std::vector<BtgFloat4> lin1, ang1, lin2, ang2;
    {
        cl::Context first(device);
        damped(first, &lin1, &ang1);
    }
    const size_t before = cl::programsBuiltFromBinaries();
    {
        cl::Context later(device);
        damped(later, &lin2, &ang2);
    }
    EXPECT_EQ(cl::programsBuiltFromBinaries(), before + 1);
    EXPECT_EQ(std::memcmp(lin1.data(), lin2.data(), sizeof(BtgFloat4) * n), 0);
    EXPECT_EQ(std::memcmp(ang1.data(), ang2.data(), sizeof(BtgFloat4) * n), 0);
    // and the damping did something (the comparison is not of untouched inputs)
    EXPECT_NE(std::memcmp(lin1.data(), lin.data(), sizeof(BtgFloat4) * n), 0);
}
