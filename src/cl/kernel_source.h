// kernel_source.h — kernel program text by stem: embedded at build time (kernels/*.cl with
// kernels/shared/ includes inlined under #line markers), or read from BTGPU_KERNEL_DIR when
// that development override is set.
#pragma once
#include <string>
#include <vector>

namespace btgpu::cl {

// Full program text for a stem such as "narrowphase" or "prims/scan"; throws
// std::runtime_error naming the stem when there is none.
std::string kernelSource(const std::string& stem);

// Every embedded stem (the kernel-build test compiles them all).
std::vector<std::string> kernelStems();

// Reads kernelDir/stem.cl and inlines its quoted #includes (relative to kernelDir), once each,
// except a header whose first line says "inlined at every include" (kernel_inline.cpp).
std::string inlineKernelFile(const std::string& kernelDir, const std::string& relPath);

}  // namespace btgpu::cl
