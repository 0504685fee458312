// test_device.h — the one OpenCL context a test process shares (so each program is built
// once per process), and small helpers for comparing device output with CPU references.
#pragma once
#include "cl/context.h"
#include "cl/launch.h"

namespace btgpu::test {

// The device chosen by the default rule / BTGPU_DEVICE; created on first use.
cl::Context& context();

}  // namespace btgpu::test
