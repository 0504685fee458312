// context.cpp — device enumeration and choice, context and queue creation, program cache.
#include "cl/context.h"

#include "cl/program.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>

namespace btgpu::cl {

static std::string platformString(cl_platform_id p, cl_platform_info what)
{
    size_t n = 0;
    BTGPU_CL_CHECK(clGetPlatformInfo(p, what, 0, nullptr, &n));
    std::string s(n, '\0');
    BTGPU_CL_CHECK(clGetPlatformInfo(p, what, n, s.data(), nullptr));
    while (!s.empty() && s.back() == '\0') s.pop_back();
    return s;
}

static std::string deviceString(cl_device_id d, cl_device_info what)
{
    size_t n = 0;
    BTGPU_CL_CHECK(clGetDeviceInfo(d, what, 0, nullptr, &n));
    std::string s(n, '\0');
    BTGPU_CL_CHECK(clGetDeviceInfo(d, what, n, s.data(), nullptr));
    while (!s.empty() && s.back() == '\0') s.pop_back();
    return s;
}

std::string DeviceInfo::describe() const { return deviceName + " (" + platformName + (isGpu ? ", GPU)" : ", CPU)"); }

std::vector<DeviceInfo> listDevices()
{
    std::vector<DeviceInfo> out;
    cl_uint np = 0;
    cl_int err = clGetPlatformIDs(0, nullptr, &np);
    if (err != CL_SUCCESS || np == 0) return out;  // no ICD installed: the caller falls back
    std::vector<cl_platform_id> platforms(np);
    BTGPU_CL_CHECK(clGetPlatformIDs(np, platforms.data(), nullptr));
    for (cl_platform_id p : platforms) {
        cl_uint nd = 0;
        if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &nd) != CL_SUCCESS || nd == 0) continue;
        std::vector<cl_device_id> devices(nd);
        BTGPU_CL_CHECK(clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, nd, devices.data(), nullptr));
        for (cl_device_id d : devices) {
            DeviceInfo info;
            info.platform = p;
            info.device = d;
            info.platformName = platformString(p, CL_PLATFORM_NAME);
            info.deviceName = deviceString(d, CL_DEVICE_NAME);
            cl_device_type type = 0;
            BTGPU_CL_CHECK(clGetDeviceInfo(d, CL_DEVICE_TYPE, sizeof(type), &type, nullptr));
            info.isGpu = (type & CL_DEVICE_TYPE_GPU) != 0;
            cl_device_fp_config fp = 0;
            BTGPU_CL_CHECK(clGetDeviceInfo(d, CL_DEVICE_SINGLE_FP_CONFIG, sizeof(fp), &fp, nullptr));
            info.correctlyRoundedSqrt = (fp & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
            BTGPU_CL_CHECK(clGetDeviceInfo(d, CL_DEVICE_MAX_WORK_GROUP_SIZE, sizeof(size_t), &info.maxWorkGroupSize, nullptr));
            BTGPU_CL_CHECK(clGetDeviceInfo(d, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof(cl_ulong), &info.globalMemBytes, nullptr));
            BTGPU_CL_CHECK(clGetDeviceInfo(d, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof(cl_uint), &info.computeUnits, nullptr));
            BTGPU_CL_CHECK(clGetDeviceInfo(d, CL_DEVICE_LOCAL_MEM_SIZE, sizeof(cl_ulong), &info.localMemBytes, nullptr));
            out.push_back(info);
        }
    }
    return out;
}

static std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

DeviceInfo selectDevice(const std::string& preference)
{
    const char* env = std::getenv("BTGPU_DEVICE");
    std::string want = lower(env && *env ? env : preference);
    std::vector<DeviceInfo> all = listDevices();
    if (all.empty()) throw Error("clGetPlatformIDs (no OpenCL platform)", CL_DEVICE_NOT_FOUND, __FILE__, __LINE__);
    auto pick = [&](auto pred) -> const DeviceInfo* {
        for (const DeviceInfo& d : all)
            if (pred(d)) return &d;
        return nullptr;
    };
    const DeviceInfo* found = nullptr;
    if (want.empty() || want == "default") {
        found = pick([](const DeviceInfo& d) { return d.isGpu; });
        if (!found) found = &all.front();
    } else if (want == "gpu") {
        found = pick([](const DeviceInfo& d) { return d.isGpu; });
    } else if (want == "cpu") {
        found = pick([](const DeviceInfo& d) { return !d.isGpu; });
    } else {
        found = pick([&](const DeviceInfo& d) {
            return lower(d.deviceName).find(want) != std::string::npos ||
                   lower(d.platformName).find(want) != std::string::npos;
        });
    }
    if (!found) throw Error("selectDevice(\"" + want + "\": no such OpenCL device)", CL_DEVICE_NOT_FOUND, __FILE__, __LINE__);
    return *found;
}

Context::Context(const DeviceInfo& device) : m_device(device)
{
    cl_int err = CL_SUCCESS;
    cl_context_properties props[] = {CL_CONTEXT_PLATFORM, (cl_context_properties)device.platform, 0};
    m_context = clCreateContext(props, 1, &device.device, nullptr, nullptr, &err);
    if (err != CL_SUCCESS) fail("clCreateContext", err, __FILE__, __LINE__);
    m_queue = clCreateCommandQueue(m_context, device.device, CL_QUEUE_PROFILING_ENABLE, &err);
    if (err != CL_SUCCESS) {
        clReleaseContext(m_context);
        fail("clCreateCommandQueue", err, __FILE__, __LINE__);
    }
}

Context::~Context()
{
    m_programs.clear();
    if (m_queue) {
        clFinish(m_queue);
        clReleaseCommandQueue(m_queue);
    }
    if (m_context) clReleaseContext(m_context);
}

Program& Context::program(const std::string& stem, const std::string& extraOptions)
{
    std::string key = stem + "|" + extraOptions;
    auto it = m_programs.find(key);
    if (it != m_programs.end()) return *it->second;
    auto t0 = std::chrono::steady_clock::now();
    auto p = std::make_unique<Program>(*this, stem, extraOptions);
    m_buildSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    Program& ref = *p;
    m_programs.emplace(key, std::move(p));
    m_built.push_back(stem);
    return ref;
}

void Context::finish() { BTGPU_CL_CHECK(clFinish(m_queue)); }

}  // namespace btgpu::cl
