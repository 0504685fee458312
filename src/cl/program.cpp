// program.cpp — builds programs from kernel sources, reports build logs, caches kernels.
#include "cl/program.h"

#include "cl/context.h"
#include "cl/kernel_source.h"

#include <cstdio>
#include <cstdlib>
#include <atomic>
#include <map>
#include <mutex>
#include <vector>

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

namespace {

// The device binaries of the programs this process has built, by device, options and source:
// a later context on the same device (each world has its own; a test process makes hundreds)
// builds from the binary instead of the source. PoCL builds 12 programs from its warm cache in
// 300-360 ms (it preprocesses each source to find its cache entry) and from their binaries in
// 34 ms. A binary the driver refuses is dropped and the source built, as the first time.
class BinaryCache {
public:
    static std::string key(cl_device_id device, const std::string& options, const std::string& source)
    {
        char id[32];
        std::snprintf(id, sizeof id, "%p|", static_cast<void*>(device));
        return id + options + "|" + source;
    }
    bool find(const std::string& k, std::vector<unsigned char>* binary)
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        auto it = m_binaries.find(k);
        if (it == m_binaries.end()) return false;
        *binary = it->second;
        return true;
    }
    void keep(const std::string& k, std::vector<unsigned char> binary)
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_binaries[k] = std::move(binary);
    }
    void drop(const std::string& k)
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_binaries.erase(k);
    }

private:
    std::mutex m_mutex;
    std::map<std::string, std::vector<unsigned char>> m_binaries;
};

BinaryCache& binaryCache()
{
    static BinaryCache cache;
    return cache;
}

std::atomic<size_t> g_fromBinaries{0};

// The built program's binary for its one device; empty when the driver gives none.
std::vector<unsigned char> programBinary(cl_program program)
{
    size_t size = 0;
    if (clGetProgramInfo(program, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, nullptr) != CL_SUCCESS || size == 0)
        return {};
    std::vector<unsigned char> binary(size);
    unsigned char* data = binary.data();
    if (clGetProgramInfo(program, CL_PROGRAM_BINARIES, sizeof data, &data, nullptr) != CL_SUCCESS) return {};
    return binary;
}

// The program from a binary this process built before; nullptr when there is none or the
// driver does not take it back.
cl_program programFromBinary(Context& context, const std::string& key, const std::string& options)
{
    std::vector<unsigned char> binary;
    if (!binaryCache().find(key, &binary)) return nullptr;
    cl_device_id dev = context.device().device;
    const unsigned char* data = binary.data();
    const size_t size = binary.size();
    cl_int status = CL_SUCCESS, err = CL_SUCCESS;
    cl_program program = clCreateProgramWithBinary(context.context(), 1, &dev, &size, &data, &status, &err);
    if (err == CL_SUCCESS && status == CL_SUCCESS && clBuildProgram(program, 1, &dev, options.c_str(), nullptr, nullptr) == CL_SUCCESS) {
        ++g_fromBinaries;
        return program;
    }
    if (program) clReleaseProgram(program);
    binaryCache().drop(key);
    return nullptr;
}

}  // namespace

size_t programsBuiltFromBinaries() { return g_fromBinaries.load(); }

Program::Program(Context& context, const std::string& stem, const std::string& extraOptions) : m_stem(stem)
{
    std::string src = kernelSource(stem);
    std::string opts = baseBuildOptions(context) + (extraOptions.empty() ? "" : " " + extraOptions);
    cl_device_id dev = context.device().device;
    const std::string cacheKey = BinaryCache::key(dev, opts, src);
    m_program = programFromBinary(context, cacheKey, opts);
    if (m_program) return;
    const char* text = src.c_str();
    size_t len = src.size();
    cl_int err = CL_SUCCESS;
    m_program = clCreateProgramWithSource(context.context(), 1, &text, &len, &err);
    if (err != CL_SUCCESS) fail("clCreateProgramWithSource", err, __FILE__, __LINE__);
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
    std::vector<unsigned char> binary = programBinary(m_program);
    if (!binary.empty()) binaryCache().keep(cacheKey, std::move(binary));
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
