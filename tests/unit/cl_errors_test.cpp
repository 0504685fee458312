// cl_errors_test.cpp — OpenCL failures say what failed: the call, the error's name, and for a
// program build the compiler's log (here from a deliberately broken kernel loaded through the
// BTGPU_KERNEL_DIR development override).
#include "cl/error.h"
#include "cl/program.h"
#include "test_device.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <gtest/gtest.h>
#include <string>

using namespace btgpu;

TEST(ClErrors, NamesTheCallAndTheError)
{
    EXPECT_STREQ(cl::errorName(CL_INVALID_KERNEL_NAME), "CL_INVALID_KERNEL_NAME");
    cl::Error e("clEnqueueNDRangeKernel", CL_OUT_OF_RESOURCES, "file.cpp", 12);
    std::string what = e.what();
    EXPECT_NE(what.find("clEnqueueNDRangeKernel"), std::string::npos);
    EXPECT_NE(what.find("CL_OUT_OF_RESOURCES"), std::string::npos);
    EXPECT_NE(what.find("file.cpp:12"), std::string::npos);
}

TEST(ClErrors, BrokenProgramCarriesItsBuildLog)
{
    char dir[] = "/tmp/btgpu_broken_XXXXXX";
    ASSERT_NE(mkdtemp(dir), nullptr);
    std::ofstream(std::string(dir) + "/broken.cl") << "__kernel void k(__global int* a) { a[0] = undeclared_name; }\n";
    setenv("BTGPU_KERNEL_DIR", dir, 1);
    cl::Context& ctx = test::context();
    try {
        ctx.program("broken");
        ADD_FAILURE() << "the broken program built";
    } catch (const cl::Error& e) {
        std::string what = e.what();
        EXPECT_NE(what.find("clBuildProgram(broken.cl"), std::string::npos) << what;
        EXPECT_NE(what.find("CL_BUILD_PROGRAM_FAILURE"), std::string::npos) << what;
        EXPECT_NE(e.buildLog().find("undeclared_name"), std::string::npos) << e.buildLog();
    }
    unsetenv("BTGPU_KERNEL_DIR");
    std::remove((std::string(dir) + "/broken.cl").c_str());
    std::remove(dir);
    // A missing kernel in a good program names the program and the kernel.
    try {
        ctx.program("probe").kernel("no_such_kernel");
        ADD_FAILURE() << "found a kernel that does not exist";
    } catch (const cl::Error& e) {
        EXPECT_NE(std::string(e.what()).find("probe::no_such_kernel"), std::string::npos) << e.what();
    }
}

// Error messages name sources relative to the project (no build machine's absolute path).
TEST(ClErrors, MessagesNameSourcesRelativeToTheProject)
{
    try {
        test::context().program("probe").kernel("no_such_kernel");
        ADD_FAILURE() << "found a kernel that does not exist";
    } catch (const std::exception& e) {
        std::string what = e.what();
        EXPECT_NE(what.find(" at src/cl/"), std::string::npos) << what;
        EXPECT_EQ(what.find(BTGPU_SOURCE_DIR), std::string::npos) << what;
    }
}
