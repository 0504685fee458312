// kernel_source.cpp — lookup of the embedded program texts, or of kernel files on disk when
// BTGPU_KERNEL_DIR is set.
#include "cl/kernel_source.h"

#include <cstdlib>
#include <stdexcept>

// Defined in the generated embedded_kernels.cpp.
namespace btgpu::cl::embedded {
struct Entry {
    const char* stem;
    const char* text;
};
extern const Entry kEntries[];
extern const unsigned kCount;
}  // namespace btgpu::cl::embedded

namespace btgpu::cl {

std::string kernelSource(const std::string& stem)
{
    const char* dir = std::getenv("BTGPU_KERNEL_DIR");
    if (dir && *dir) return inlineKernelFile(dir, stem + ".cl");
    for (unsigned i = 0; i < embedded::kCount; ++i)
        if (stem == embedded::kEntries[i].stem) return embedded::kEntries[i].text;
    throw std::runtime_error("btgpu: no kernel program named '" + stem + "'");
}

std::vector<std::string> kernelStems()
{
    std::vector<std::string> out;
    for (unsigned i = 0; i < embedded::kCount; ++i) out.push_back(embedded::kEntries[i].stem);
    return out;
}

}  // namespace btgpu::cl
