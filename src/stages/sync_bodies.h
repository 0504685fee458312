// sync_bodies.h — Stage: sync_in / sync_out. The host side of the device world: sizing the
// body columns, writing only the rows the app changed (one scatter launch), and the one
// readback per stepSimulation call (transforms, velocities, counters together).
#pragma once
#include "cl/pinned.h"
#include "world/device_world.h"

#include <vector>

namespace btgpu {

// One changed body row as the host sends it.
struct BodyRowUpdate {
    int row;
    BtgFloat4 pos, rot, linVel, angVel, force, torque;
    BtgBodyProps props;
};

// Sizes every body column for n rows (contents of new rows undefined until written).
void resizeBodies(DeviceWorld& w, int n);
// Writes the given rows through staging buffers and one scatter launch.
void syncIn(DeviceWorld& w, const std::vector<BodyRowUpdate>& rows);
// Clears the sleeping and island timers of rows that now hold a new body.
void resetRows(DeviceWorld& w, const std::vector<int>& rows);

// In page-locked host memory (cl/pinned.h): the readback is the step's one large transfer.
// Release before the context goes.
struct BodyReadback {
    cl::PinnedArray<BtgFloat4> pos, rot, linVel, angVel;
    cl::PinnedArray<uint> sleepState;  // 1: asleep
    cl::PinnedArray<uint> counters;
    // The call's contact reports (report_contacts), when that stage ran: contacts[0, numContacts).
    cl::PinnedArray<BtgContactReport> contacts;
    size_t numContacts = 0;
    bool contactsValid = false;
    void release()
    {
        pos.release();
        rot.release();
        linVel.release();
        angVel.release();
        sleepState.release();
        counters.release();
        contacts.release();
        numContacts = 0;
        contactsValid = false;
    }
};
// Blocking readback of every row's state and the counters.
void syncOut(DeviceWorld& w, BodyReadback& out);

}  // namespace btgpu
