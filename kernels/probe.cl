/* probe.cl — Stage: none; a self-check run by tests on each device.
 * Launch: one work-item. Writes the sizes of the shared structs as the device compiler sees
 * them, and a float expression whose value differs when a*b+c is contracted into an fma. */
#include "shared/types.h"
#include "shared/math.h"
#include "shared/joint_rows.h"

__kernel void probe_layout(__global int* out, float a, float b, float c)
{
    if (get_global_id(0) != 0) return;
    out[0] = (int)sizeof(BtgBodyProps);
    out[1] = (int)sizeof(BtgShape);
    out[2] = (int)sizeof(BtgFace);
    out[3] = (int)sizeof(BtgPair);
    out[4] = (int)sizeof(BtgManifold);
    out[5] = (int)sizeof(BtgContact);
    out[6] = (int)sizeof(BtgStepParams);
    out[8] = (int)sizeof(BtgCachedContact);
    out[9] = (int)sizeof(BtgEdge);
    out[10] = (int)sizeof(BtgManifoldPoint);
    out[11] = (int)sizeof(BtgManifoldRange);
    out[12] = (int)sizeof(BtgPersistentManifold);
    BtgShape shape;
    out[13] = (int)((char*)&shape.convexType - (char*)&shape);
    out[14] = (int)sizeof(BtgJoint);
    out[15] = (int)sizeof(BtgJointRow);
    out[16] = (int)sizeof(BtgJointState);
    out[17] = (int)sizeof(BtgJointFeedback);
    float r = a * b + c; /* with contraction this is fma(a, b, c): a different float */
    out[7] = as_int(r);
}
