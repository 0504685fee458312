// sync_bodies.h — Stage: sync_in / sync_out. The host side of the device world: sizing the
// body columns, writing only the rows the app changed (one scatter launch), and the one
// readback per stepSimulation call (transforms, velocities, counters together).
#pragma once
#include "cl/pinned.h"
#include "world/device_world.h"
#include "world/untouched_vector.h"

#include <vector>

namespace btgpu {

// One changed body row as the host sends it.
struct BodyRowUpdate {
    int row;
    BtgFloat4 pos, rot, linVel, angVel, force, torque;
    BtgBodyProps props;
};

// The rows an app changed, held as syncIn uploads them (row numbers, six states a row, props):
// built in place, never repacked. (The rebuild's every row goes as BodyColumns instead.)
struct BodyRowUploads {
    std::vector<int> rows;
    std::vector<BtgFloat4> states;  // pos, rot, linVel, angVel, force, torque
    std::vector<BtgBodyProps> props;

    size_t size() const { return rows.size(); }
    bool empty() const { return rows.empty(); }
    void resize(size_t n)
    {
        rows.resize(n);
        states.resize(6 * n);
        props.resize(n);
    }
    void set(size_t i, const BodyRowUpdate& u)
    {
        rows[i] = u.row;
        BtgFloat4* s = &states[6 * i];
        s[0] = u.pos;
        s[1] = u.rot;
        s[2] = u.linVel;
        s[3] = u.angVel;
        s[4] = u.force;
        s[5] = u.torque;
        props[i] = u.props;
    }
    void add(const BodyRowUpdate& u)
    {
        resize(size() + 1);
        set(size() - 1, u);
    }
    void append(const BodyRowUploads& o)
    {
        rows.insert(rows.end(), o.rows.begin(), o.rows.end());
        states.insert(states.end(), o.states.begin(), o.states.end());
        props.insert(props.end(), o.props.begin(), o.props.end());
    }
};

// Every row 0..n-1 by column, as the body columns hold them (the rebuild's: written as they
// are, with no staging copy and no scatter). Sized without writing, filled in parallel.
struct BodyColumns {
    UntouchedVector<BtgFloat4> pos, rot, linVel, angVel, force, torque;
    UntouchedVector<BtgBodyProps> props;

    size_t size() const { return pos.size(); }
    void resize(size_t n)
    {
        for (UntouchedVector<BtgFloat4>* c : {&pos, &rot, &linVel, &angVel, &force, &torque}) c->resize(n);
        props.resize(n);
    }
    void set(size_t r, const BodyRowUpdate& u)
    {
        pos[r] = u.pos;
        rot[r] = u.rot;
        linVel[r] = u.linVel;
        angVel[r] = u.angVel;
        force[r] = u.force;
        torque[r] = u.torque;
        props[r] = u.props;
    }
};

// Sizes every body column for n rows (contents of new rows undefined until written).
void resizeBodies(DeviceWorld& w, int n);
// Writes the given rows through staging buffers and one scatter launch.
void syncIn(DeviceWorld& w, const BodyRowUploads& rows);
// Writes every row (the columns' size must be the world's numBodies).
void writeColumns(DeviceWorld& w, const BodyColumns& rows);
// Sets the rows' own deactivation timers (the app's setDeactivationTime, or activate()'s reset).
void setSleepTimes(DeviceWorld& w, const std::vector<int>& rows, const std::vector<float>& times);
// Clears the sleeping and island timers of rows that now hold a new body.
// woken: rows of sleeping bodies the app woke (their islands wake before the next solve, as
// stock's); else fresh rows.
void resetRows(DeviceWorld& w, const std::vector<int>& rows, bool woken = false);

// In page-locked host memory (cl/pinned.h): the readback is the step's one large transfer.
// Release before the context goes.
struct BodyReadback {
    cl::PinnedArray<BtgFloat4> pos, rot, linVel, angVel;
    cl::PinnedArray<uint> sleepState;  // 1: asleep
    cl::PinnedArray<float> sleepTime;  // each body's own deactivation timer (its m_deactivationTime)
    cl::PinnedArray<uint> counters;
    // The call's contact reports (report_contacts), when that stage ran: contacts[0, numContacts).
    cl::PinnedArray<BtgContactReport> contacts;
    // What the fill reads: contacts.data(), or on a CPU device the mapped device buffer
    // (DeviceWorld::reportsMapped), valid until the next call's report_contacts.
    const BtgContactReport* reports = nullptr;
    size_t numContacts = 0;
    bool contactsValid = false;
    bool reportsPending = false;  // their read still travelling: awaitReports before reading them
    void release()
    {
        pos.release();
        rot.release();
        linVel.release();
        angVel.release();
        sleepState.release();
        sleepTime.release();
        counters.release();
        contacts.release();
        reports = nullptr;
        numContacts = 0;
        contactsValid = false;
        reportsPending = false;  // (each release waits for the queue)
    }
};
// Undoes syncOut's mapping of the contact reports (a CPU device's), if any.
void unmapReports(DeviceWorld& w);
// Readback of every row's state and the counters (waited for), and of the contact reports when
// the call wrote them (queued behind: out.reportsPending until awaitReports).
void syncOut(DeviceWorld& w, BodyReadback& out);
// Waits for the contact reports' read, when one is travelling.
void awaitReports(DeviceWorld& w, BodyReadback& out);

}  // namespace btgpu
