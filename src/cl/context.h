// context.h — one OpenCL device, its context, its in-order profiling queue and its program
// cache. Device choice: BTGPU_DEVICE (gpu | cpu | substring of platform or device name)
// overrides the preference passed in; the default is the first GPU, else the first CPU device.
#pragma once
#include "cl/error.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace btgpu::cl {

struct DeviceInfo {
    cl_platform_id platform = nullptr;
    cl_device_id device = nullptr;
    std::string platformName;
    std::string deviceName;
    bool isGpu = false;
    bool correctlyRoundedSqrt = false;  // CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT is supported
    size_t maxWorkGroupSize = 1;
    cl_ulong globalMemBytes = 0;
    cl_uint computeUnits = 1;
    cl_ulong localMemBytes = 0;  // a work-group's local memory (CL_DEVICE_LOCAL_MEM_SIZE)
    std::string describe() const;
    // NVIDIA's GPUs: programs are built with -DBTG_NVIDIA=1 (inline PTX), and the host picks the
    // launches that rely on it (the soft step's quads) by the same test
    bool isNvidiaGpu() const { return isGpu && platformName.find("NVIDIA") != std::string::npos; }
    // A CPU device of a few cores, where one work-item's pass over a whole stage (the batching,
    // the radix sort) beats a launch a round: PoCL on 2 cores, cubes 8,000, 108 batching launches
    // 5.3 ms against 2.4-2.7 in one. Measured on 2 cores only; a CPU of more cores than this
    // keeps the parallel launches (the same results either way).
    static constexpr cl_uint kFewCores = 8;
    bool fewCpuCores() const { return !isGpu && computeUnits <= kFewCores; }
};

// All OpenCL devices on all platforms; empty when there is no platform (no ICD).
std::vector<DeviceInfo> listDevices();

// Picks a device by preference ("" = default rule); throws Error when none matches.
DeviceInfo selectDevice(const std::string& preference);

class Program;

class Context {
public:
    explicit Context(const DeviceInfo& device);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    cl_context context() const { return m_context; }
    cl_command_queue queue() const { return m_queue; }
    const DeviceInfo& device() const { return m_device; }

    // The built program for a kernel stem ("narrowphase", "prims/scan"), built once per
    // (stem, options) and kept for the context's life.
    Program& program(const std::string& stem, const std::string& extraOptions = {});
    // Stems built so far, in build order (the Report's proof of what the plan compiled).
    const std::vector<std::string>& builtPrograms() const { return m_built; }
    double buildSeconds() const { return m_buildSeconds; }

    void finish();

    // Device bytes this context may hold in buffers (0: no limit). A buffer past it fails as
    // an out-of-memory clCreateBuffer would (CL_MEM_OBJECT_ALLOCATION_FAILURE).
    void setMemoryLimit(size_t bytes) { m_memoryLimit = bytes; }
    size_t memoryLimit() const { return m_memoryLimit; }

private:
    DeviceInfo m_device;
    size_t m_memoryLimit = 0;
    cl_context m_context = nullptr;
    cl_command_queue m_queue = nullptr;
    std::map<std::string, std::unique_ptr<Program>> m_programs;
    std::vector<std::string> m_built;
    double m_buildSeconds = 0.0;
};

}  // namespace btgpu::cl
