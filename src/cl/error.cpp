// error.cpp — names for OpenCL status codes and the Error exception.
#include "cl/error.h"

namespace btgpu::cl {

const char* errorName(cl_int code)
{
    switch (code) {
#define BTGPU_CASE(x) case x: return #x;
        BTGPU_CASE(CL_SUCCESS)
        BTGPU_CASE(CL_DEVICE_NOT_FOUND)
        BTGPU_CASE(CL_DEVICE_NOT_AVAILABLE)
        BTGPU_CASE(CL_COMPILER_NOT_AVAILABLE)
        BTGPU_CASE(CL_MEM_OBJECT_ALLOCATION_FAILURE)
        BTGPU_CASE(CL_OUT_OF_RESOURCES)
        BTGPU_CASE(CL_OUT_OF_HOST_MEMORY)
        BTGPU_CASE(CL_PROFILING_INFO_NOT_AVAILABLE)
        BTGPU_CASE(CL_MEM_COPY_OVERLAP)
        BTGPU_CASE(CL_IMAGE_FORMAT_MISMATCH)
        BTGPU_CASE(CL_IMAGE_FORMAT_NOT_SUPPORTED)
        BTGPU_CASE(CL_BUILD_PROGRAM_FAILURE)
        BTGPU_CASE(CL_MAP_FAILURE)
        BTGPU_CASE(CL_MISALIGNED_SUB_BUFFER_OFFSET)
        BTGPU_CASE(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
        BTGPU_CASE(CL_COMPILE_PROGRAM_FAILURE)
        BTGPU_CASE(CL_LINKER_NOT_AVAILABLE)
        BTGPU_CASE(CL_LINK_PROGRAM_FAILURE)
        BTGPU_CASE(CL_DEVICE_PARTITION_FAILED)
        BTGPU_CASE(CL_KERNEL_ARG_INFO_NOT_AVAILABLE)
        BTGPU_CASE(CL_INVALID_VALUE)
        BTGPU_CASE(CL_INVALID_DEVICE_TYPE)
        BTGPU_CASE(CL_INVALID_PLATFORM)
        BTGPU_CASE(CL_INVALID_DEVICE)
        BTGPU_CASE(CL_INVALID_CONTEXT)
        BTGPU_CASE(CL_INVALID_QUEUE_PROPERTIES)
        BTGPU_CASE(CL_INVALID_COMMAND_QUEUE)
        BTGPU_CASE(CL_INVALID_HOST_PTR)
        BTGPU_CASE(CL_INVALID_MEM_OBJECT)
        BTGPU_CASE(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR)
        BTGPU_CASE(CL_INVALID_IMAGE_SIZE)
        BTGPU_CASE(CL_INVALID_SAMPLER)
        BTGPU_CASE(CL_INVALID_BINARY)
        BTGPU_CASE(CL_INVALID_BUILD_OPTIONS)
        BTGPU_CASE(CL_INVALID_PROGRAM)
        BTGPU_CASE(CL_INVALID_PROGRAM_EXECUTABLE)
        BTGPU_CASE(CL_INVALID_KERNEL_NAME)
        BTGPU_CASE(CL_INVALID_KERNEL_DEFINITION)
        BTGPU_CASE(CL_INVALID_KERNEL)
        BTGPU_CASE(CL_INVALID_ARG_INDEX)
        BTGPU_CASE(CL_INVALID_ARG_VALUE)
        BTGPU_CASE(CL_INVALID_ARG_SIZE)
        BTGPU_CASE(CL_INVALID_KERNEL_ARGS)
        BTGPU_CASE(CL_INVALID_WORK_DIMENSION)
        BTGPU_CASE(CL_INVALID_WORK_GROUP_SIZE)
        BTGPU_CASE(CL_INVALID_WORK_ITEM_SIZE)
        BTGPU_CASE(CL_INVALID_GLOBAL_OFFSET)
        BTGPU_CASE(CL_INVALID_EVENT_WAIT_LIST)
        BTGPU_CASE(CL_INVALID_EVENT)
        BTGPU_CASE(CL_INVALID_OPERATION)
        BTGPU_CASE(CL_INVALID_GL_OBJECT)
        BTGPU_CASE(CL_INVALID_BUFFER_SIZE)
        BTGPU_CASE(CL_INVALID_MIP_LEVEL)
        BTGPU_CASE(CL_INVALID_GLOBAL_WORK_SIZE)
        BTGPU_CASE(CL_INVALID_PROPERTY)
        BTGPU_CASE(CL_INVALID_IMAGE_DESCRIPTOR)
        BTGPU_CASE(CL_INVALID_COMPILER_OPTIONS)
        BTGPU_CASE(CL_INVALID_LINKER_OPTIONS)
        BTGPU_CASE(CL_INVALID_DEVICE_PARTITION_COUNT)
#undef BTGPU_CASE
        case -1001: return "CL_PLATFORM_NOT_FOUND_KHR";
        default: return "CL_UNKNOWN_ERROR";
    }
}

static std::string describe(const std::string& call, cl_int code, const char* file, int line, const std::string& log)
{
    std::string s = call + " failed: " + errorName(code) + " (" + std::to_string(code) + ") at " + file + ":" +
                    std::to_string(line);
    if (!log.empty()) s += "\n--- build log ---\n" + log;
    return s;
}

Error::Error(const std::string& call, cl_int code, const char* file, int line, const std::string& buildLog)
    : std::runtime_error(describe(call, code, file, line, buildLog)), m_code(code), m_buildLog(buildLog)
{
}

void fail(const char* call, cl_int code, const char* file, int line) { throw Error(call, code, file, line); }

}  // namespace btgpu::cl
