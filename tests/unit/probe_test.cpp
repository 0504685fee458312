// probe_test.cpp — the shared structs have the same layout on the device as on the host, and
// the device does not contract a*b+c into an fma (kernels must round like the references).
#include "cl/program.h"
#include "shared/joint_rows.h"
#include "shared/types.h"
#include "test_device.h"

#include <cstddef>
#include <cstring>
#include <gtest/gtest.h>

using namespace btgpu;

TEST(Probe, LayoutAndNoContraction)
{
    cl::Context& ctx = test::context();
    cl::DeviceArray<int> out;
    out.reserve(ctx, 18);
    // Chosen so that fma(a, b, c) and round(round(a*b) + c) differ.
    float a = 1.0f + 1.0f / 4096.0f, b = 1.0f - 1.0f / 4096.0f, c = -1.0f;
    cl::Launch(ctx, ctx.program("probe").kernel("probe_layout")).arg(out).arg(a).arg(b).arg(c).run(1, 1);
    std::vector<int> v = out.download(ctx, 18);
    EXPECT_EQ(v[0], (int)sizeof(BtgBodyProps));
    EXPECT_EQ(v[1], (int)sizeof(BtgShape));
    EXPECT_EQ(v[2], (int)sizeof(BtgFace));
    EXPECT_EQ(v[3], (int)sizeof(BtgPair));
    EXPECT_EQ(v[4], (int)sizeof(BtgManifold));
    EXPECT_EQ(v[5], (int)sizeof(BtgContact));
    EXPECT_EQ(v[6], (int)sizeof(BtgStepParams));
    EXPECT_EQ(v[8], (int)sizeof(BtgCachedContact));
    EXPECT_EQ(v[9], (int)sizeof(BtgEdge));
    EXPECT_EQ(v[10], (int)sizeof(BtgManifoldPoint));
    EXPECT_EQ(v[11], (int)sizeof(BtgManifoldRange));
    EXPECT_EQ(v[12], (int)sizeof(BtgPersistentManifold));
    EXPECT_EQ(v[13], (int)offsetof(BtgShape, convexType));
    EXPECT_EQ(v[14], (int)sizeof(BtgJoint));
    EXPECT_EQ(v[15], (int)sizeof(BtgJointRow));
    EXPECT_EQ(v[16], (int)sizeof(BtgJointState));
    EXPECT_EQ(v[17], (int)sizeof(BtgJointFeedback));
    volatile float va = a, vb = b, vc = c;
    float host = va * vb + vc;
    float dev;
    std::memcpy(&dev, &v[7], 4);
    EXPECT_EQ(dev, host) << "device contracted a*b+c into an fma";
}
