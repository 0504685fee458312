// report_contacts.h — Stage: the solved contact manifolds of a call's last substep packed for
// the host (the app's dispatcher manifolds, compat/manifold_sync.cpp), read back with the call's
// one readback (syncOut). Reads contacts, contactManifolds, manifolds, counters, pos, rot.
// Writes the reports (w.reports: contactReports, or with overSoftRows the soft step's rows'
// storage, dead after its solve) and sets contactReportsWritten.
#pragma once
#include "world/device_world.h"

namespace btgpu {
void reportContacts(DeviceWorld& w, bool overSoftRows = false);
}
