// program.cpp — builds programs from kernel sources, reports build logs, caches kernels.
#include "cl/program.h"

#include "cl/context.h"
#include "cl/kernel_source.h"

#include <cstdio>
#include <cstdlib>

namespace btgpu::cl {

std::string baseBuildOptions(const Context& context)
{
    std::string opts = "-cl-std=CL1.2";
    if (context.device().correctlyRoundedSqrt) opts += " -cl-fp32-correctly-rounded-divide-sqrt";
    // Data the resident kernels share between work-groups is read through volatile pointers
    // on GPUs, whose per-compute-unit caches are not coherent; CPU caches are, and there
    // volatile only stops the compiler from vectorizing (PoCL: the solve ran 2x slower).
    opts += context.device().isGpu ? " -DBTG_SHARED=volatile" : " -DBTG_SHARED= -DBTG_CPU_DEVICE=1";
    // NVIDIA's GPUs: a program may read that data with PTX's ld.global.cg instead (L2, coherent
    // across compute units) and drop volatile (solve_soft.cl does: its solve stage 2% faster on
    // the H100, the same state hashes).
    if (context.device().isNvidiaGpu()) opts += " -DBTG_NVIDIA=1";
    // For measuring (not for apps): BTGPU_CL_OPTIONS adds build options (NVIDIA's
    // -cl-nv-verbose, -cl-nv-maxrregcount=N, ...), BTGPU_CL_LOG=1 prints every build's log.
    if (const char* extra = std::getenv("BTGPU_CL_OPTIONS"); extra && *extra) opts += std::string(" ") + extra;
    return opts;
}

Program::Program(Context& context, const std::string& stem, const std::string& extraOptions) : m_stem(stem)
{
    std::string src = kernelSource(stem);
    const char* text = src.c_str();
    size_t len = src.size();
    cl_int err = CL_SUCCESS;
    m_program = clCreateProgramWithSource(context.context(), 1, &text, &len, &err);
    if (err != CL_SUCCESS) fail("clCreateProgramWithSource", err, __FILE__, __LINE__);
    std::string opts = baseBuildOptions(context) + (extraOptions.empty() ? "" : " " + extraOptions);
    cl_device_id dev = context.device().device;
    err = clBuildProgram(m_program, 1, &dev, opts.c_str(), nullptr, nullptr);
    if (err != CL_SUCCESS) {
        size_t n = 0;
        clGetProgramBuildInfo(m_program, dev, CL_PROGRAM_BUILD_LOG, 0, nullptr, &n);
        std::string log(n, '\0');
        if (n) clGetProgramBuildInfo(m_program, dev, CL_PROGRAM_BUILD_LOG, n, log.data(), nullptr);
        clReleaseProgram(m_program);
        m_program = nullptr;
        throw Error("clBuildProgram(" + stem + ".cl, \"" + opts + "\")", err, __FILE__, __LINE__, log);
    }
    if (const char* e = std::getenv("BTGPU_CL_LOG"); e && e[0] == '1') {
        size_t n = 0;
        clGetProgramBuildInfo(m_program, dev, CL_PROGRAM_BUILD_LOG, 0, nullptr, &n);
        std::string log(n, '\0');
        if (n) clGetProgramBuildInfo(m_program, dev, CL_PROGRAM_BUILD_LOG, n, log.data(), nullptr);
        std::fprintf(stderr, "btgpu: build log of %s.cl (%s):\n%s\n", stem.c_str(), opts.c_str(), log.c_str());
    }
}

Program::~Program()
{
    for (auto& k : m_kernels) clReleaseKernel(k.second);
    if (m_program) clReleaseProgram(m_program);
}

cl_kernel Program::kernel(const std::string& name)
{
    auto it = m_kernels.find(name);
    if (it != m_kernels.end()) return it->second;
    cl_int err = CL_SUCCESS;
    cl_kernel k = clCreateKernel(m_program, name.c_str(), &err);
    if (err != CL_SUCCESS) fail(("clCreateKernel(" + m_stem + "::" + name + ")").c_str(), err, __FILE__, __LINE__);
    m_kernels.emplace(name, k);
    return k;
}

size_t kernelWorkGroupSize(const Context& context, cl_kernel kernel)
{
    size_t size = 0;
    BTGPU_CL_CHECK(clGetKernelWorkGroupInfo(kernel, context.device().device, CL_KERNEL_WORK_GROUP_SIZE, sizeof(size),
                                            &size, nullptr));
    return size;
}

}  // namespace btgpu::cl
