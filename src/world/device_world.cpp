// device_world.cpp — the world's device state going: a mapping of its contact reports
// (syncOut's, on CPU devices) is undone before the buffers are released.
#include "world/device_world.h"

#include "stages/sync_bodies.h"

namespace btgpu {

DeviceWorld::~DeviceWorld()
{
    try {
        if (reportsMapped) {
            unmapReports(*this);
            ctx.finish();
        }
    } catch (...) {
        // A lost device: its buffers go with the context all the same.
    }
}

}  // namespace btgpu
