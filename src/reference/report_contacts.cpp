// report_contacts.cpp (reference) — see report_contacts.h.
#include "reference/report_contacts.h"

namespace btgpu::ref {

std::vector<BtgContactReport> reportContacts(const std::vector<BtgContact>& contacts,
                                             const std::vector<uint>& contactManifolds,
                                             const std::vector<BtgManifold>& manifolds,
                                             const std::vector<BtgFloat4>& pos, const std::vector<BtgFloat4>& rot)
{
    std::vector<BtgContactReport> out;
    out.reserve(contacts.size());
    for (size_t i = 0; i < contacts.size(); ++i) {
        const BtgManifold& m = manifolds[contactManifolds[i]];
        out.push_back(btgContactReportFrom(&contacts[i], m, pos[size_t(m.bodyA)], rot[size_t(m.bodyA)],
                                           pos[size_t(m.bodyB)], rot[size_t(m.bodyB)]));
    }
    return out;
}

}  // namespace btgpu::ref
