// program.h — one built OpenCL program and its kernels, looked up by name once.
#pragma once
#include "cl/error.h"

#include <map>
#include <string>

namespace btgpu::cl {

class Context;

class Program {
public:
    // Builds the kernel stem's source (embedded, or from BTGPU_KERNEL_DIR) for the context's
    // device; a failed build throws Error with the full build log.
    Program(Context& context, const std::string& stem, const std::string& extraOptions);
    ~Program();
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;

    cl_kernel kernel(const std::string& name);
    const std::string& stem() const { return m_stem; }

private:
    std::string m_stem;
    cl_program m_program = nullptr;
    std::map<std::string, cl_kernel> m_kernels;
};

// Programs this process built from the binary of an earlier build of the same source, options
// and device (a later context's: see program.cpp), for tests and diagnostics.
size_t programsBuiltFromBinaries();

// The largest work-group this kernel runs with on the context's device.
size_t kernelWorkGroupSize(const Context& context, cl_kernel kernel);

// Options every program is built with: OpenCL C 1.2, no fast-relaxed math, correctly
// rounded sqrt/divide where the device offers it (so kernels track the CPU references).
std::string baseBuildOptions(const Context& context);

}  // namespace btgpu::cl
