// report_contacts.h (reference) — the contact report on the CPU: the same packing
// (kernels/shared/contact_report.h) of each contact with its manifold.
#pragma once
#include "shared/contact_report.h"

#include <vector>

namespace btgpu::ref {

std::vector<BtgContactReport> reportContacts(const std::vector<BtgContact>& contacts,
                                             const std::vector<uint>& contactManifolds,
                                             const std::vector<BtgManifold>& manifolds,
                                             const std::vector<BtgFloat4>& pos, const std::vector<BtgFloat4>& rot);

}  // namespace btgpu::ref
