// error.h — OpenCL failures as exceptions inside the library: the call, the error name,
// file:line and, for program builds, the full build log. The world catches them at its
// public boundary (stepSimulation never throws) and turns them into a Report entry.
#pragma once
#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>

#include <stdexcept>
#include <string>

namespace btgpu::cl {

const char* errorName(cl_int code);

class Error : public std::runtime_error {
public:
    Error(const std::string& call, cl_int code, const char* file, int line, const std::string& buildLog = {});
    cl_int code() const { return m_code; }
    const std::string& buildLog() const { return m_buildLog; }

private:
    cl_int m_code;
    std::string m_buildLog;
};

[[noreturn]] void fail(const char* call, cl_int code, const char* file, int line);

}  // namespace btgpu::cl

// Checks one cl* call that returns its status.
#define BTGPU_CL_CHECK(call)                                                   \
    do {                                                                       \
        cl_int btgpu_err_ = (call);                                            \
        if (btgpu_err_ != CL_SUCCESS) ::btgpu::cl::fail(#call, btgpu_err_, __FILE__, __LINE__); \
    } while (0)
