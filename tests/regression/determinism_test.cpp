// determinism_test.cpp — same scene, same device, same binary: bitwise the same states in
// another process, whatever PoCL's thread count and work-group size limit, and a machine with
// no OpenCL platform at all runs the CPU path with a named Device issue. Each case runs this
// test binary again as a child (the OpenCL loader reads its environment once per process).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "cl/context.h"
#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

namespace {

constexpr int kSteps = 90;

// The hashes of a pile of boxes, every 10 steps, and what the world said of itself: in the
// bullet mode, and a larger pile with the library's default (the soft step; past 2,048
// contacts a CPU device takes its per-colour launches, below them one launch).
std::string runScene()
{
    std::ostringstream out;
    for (const bool byDefault : {false, true}) {
        ScenePtr scene = byDefault ? scenes::makeScene("cubes:10x10x10", WorldKind::Gpu, Config())
                                   : scenes::makeScene("cubes:5x4x5", WorldKind::Gpu);
        for (int i = 1; i <= kSteps; ++i) {
            scene->step();
            if (i % 10 == 0) out << "hash " << std::hex << scene->gpuWorld()->stateHash() << std::dec << "\n";
        }
        const Report& r = *scene->report();
        out << "gpuPath " << r.gpuPath << " solver " << int(r.solver) << "\n";
        for (const Issue& issue : r.issues)
            if (issue.kind == Issue::Kind::Device) out << "device issue\n";
    }
    return out.str();
}

std::string selfPath()
{
    char buf[4096];
    ssize_t n = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
    if (n <= 0) return "";
    buf[n] = 0;
    return buf;
}

// Set when a child found no device the parent has: NVIDIA GPUs in exclusive-process compute
// mode admit one process, and the driver keeps it for the parent once it has run a world.
bool g_deviceNotShared = false;

// Runs the Child case in a new process with `env` prepended; its output file's text.
std::string runChild(const std::string& env, bool device = false)
{
    const std::string out = testing::TempDir() + "btgpu_determinism_" + std::to_string(getpid()) + ".txt";
    std::remove(out.c_str());
    const std::string log = out + ".log";
    const std::string cmd = env + (device ? " BTGPU_DETERMINISM_DEVICE=1" : "") + " BTGPU_DETERMINISM_OUT=" + out + " '" + selfPath() +
                            "' --gtest_filter=Determinism.Child > '" + log + "' 2>&1";
    if (std::system(cmd.c_str()) != 0) {
        std::ifstream childLog(log);
        std::stringstream text;
        text << childLog.rdbuf();
        if (text.str().find("no such OpenCL device") != std::string::npos && env.find("OCL_ICD") == std::string::npos)
            g_deviceNotShared = true;
        else
            ADD_FAILURE() << cmd << "\n" << text.str();
    }
    std::remove(log.c_str());
    std::ifstream in(out);
    std::stringstream text;
    text << in.rdbuf();
    std::remove(out.c_str());
    return text.str();
}

}  // namespace

// Not a test on its own: what a child process runs (skipped unless a parent asked for it).
TEST(Determinism, Child)
{
    const char* out = std::getenv("BTGPU_DETERMINISM_OUT");
    if (!out) GTEST_SKIP() << "run by Determinism.AcrossProcesses";
    std::ofstream file(out);
    file << runScene();
    // What the device offered this process (the parent checks its settings took effect).
    if (std::getenv("BTGPU_DETERMINISM_DEVICE")) {
        const cl::DeviceInfo d = cl::selectDevice("");  // what the world chose, without a second context
        file << "cu " << d.computeUnits << " wg " << d.maxWorkGroupSize << "\n";
    }
}

TEST(Determinism, AcrossProcessesThreadsAndGroupSizes)
{
    const std::string here = runScene();
    ASSERT_NE(here.find("gpuPath 1 solver 0\n"), std::string::npos) << here;  // the bullet mode
    ASSERT_NE(here.find("gpuPath 1 solver 2\n"), std::string::npos) << here;  // the default's soft step
    // PoCL's CPU device: compute units (threads) and the largest work-group it offers, which
    // set the launch shapes the stages choose. Ignored by other drivers.
    struct Case {
        const char* env;
        const char* offered;  // what PoCL's device must then say, "" for any
    };
    // No context held here while the children run: a GPU in exclusive-process mode would refuse
    // them the device.
    const bool pocl = cl::selectDevice("").platformName.find("Portable") != std::string::npos;
    for (const Case& c : {Case{"", ""}, Case{"POCL_CPU_MAX_CU_NUM=1 POCL_MAX_PTHREAD_COUNT=1", "cu 1 "},
                          Case{"POCL_CPU_MAX_CU_NUM=3 POCL_MAX_PTHREAD_COUNT=3", "cu 3 "},
                          Case{"POCL_MAX_WORK_GROUP_SIZE=64", "wg 64\n"}}) {
        SCOPED_TRACE(c.env);
        std::string child = runChild(c.env, true);
        if (g_deviceNotShared) GTEST_SKIP() << "the device admits no second process (exclusive compute mode)";
        size_t cut = child.find("cu ");
        ASSERT_NE(cut, std::string::npos) << child;
        if (pocl) EXPECT_NE(child.find(c.offered, cut), std::string::npos) << child.substr(cut);
        EXPECT_EQ(child.substr(0, cut), here);
    }
}

TEST(Determinism, NoOpenClPlatformRunsTheCpuPathAndSaysSo)
{
    const std::string child = runChild("OCL_ICD_VENDORS=/nonexistent-btgpu-vendors OCL_ICD_FILENAMES=");
    EXPECT_NE(child.find("gpuPath 0"), std::string::npos) << child;
    EXPECT_NE(child.find("device issue"), std::string::npos) << child;
}
