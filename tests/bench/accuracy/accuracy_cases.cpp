// accuracy_cases.cpp — the probes (analytic trajectory, stopping distance, bounce apexes,
// momentum and energy drift, resting drift, pile statistics) and the case list.
#include "accuracy_cases.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace btgpu::accuracy {

using scenes::AccuracyScene;

namespace {

constexpr double kG = 10.0;  // m/s^2, every scene's gravity (downwards)
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// The dynamic bodies of copy c, in creation order.
const btRigidBody* body(const AccuracyScene& a, int c, int k)
{
    return a.scene->body(a.firstBody + c * a.bodiesPerCopy + k);
}

std::string fmt(const char* key, double v)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s=%.4g;", key, v);
    return buf;
}

// Position against the continuous solution p0 + v0 t + g t^2 / 2, at the end of the run.
class TrajectoryProbe : public Probe {
public:
    void sample(const AccuracyScene& a, int frame, double t) override
    {
        const int n = a.copies * a.bodiesPerCopy;
        if (frame == 0) {
            for (int i = 0; i < n; ++i) {
                const btRigidBody* b = a.scene->body(a.firstBody + i);
                m_p0.push_back(b->getWorldTransform().getOrigin());
                m_v0.push_back(b->getLinearVelocity());
            }
        }
        double sum = 0;
        for (int i = 0; i < n; ++i) {
            const btVector3& p = a.scene->body(a.firstBody + i)->getWorldTransform().getOrigin();
            const double exact[3] = {m_p0[i].x() + m_v0[i].x() * t, m_p0[i].y() + m_v0[i].y() * t - 0.5 * kG * t * t,
                                     m_p0[i].z() + m_v0[i].z() * t};
            const double d[3] = {p.x() - exact[0], p.y() - exact[1], p.z() - exact[2]};
            sum += std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        }
        m_last = sum / n;
    }
    Measurement finish(const AccuracyScene&) override { return {m_last, 0, ""}; }

private:
    std::vector<btVector3> m_p0, m_v0;
    double m_last = kNaN;
};

// Distance slid against v^2 / (2 mu g); x only (the box should not turn or drift sideways).
class SlideProbe : public Probe {
public:
    void sample(const AccuracyScene& a, int frame, double) override
    {
        if (frame == 0)
            for (int c = 0; c < a.copies; ++c) m_x0.push_back(body(a, c, 0)->getWorldTransform().getOrigin().x());
    }
    Measurement finish(const AccuracyScene& a) override
    {
        const double exact = scenes::kSlideSpeed * scenes::kSlideSpeed / (2 * scenes::kSlideFriction * kG);
        double sum = 0, slid = 0;
        for (int c = 0; c < a.copies; ++c) {
            const double d = body(a, c, 0)->getWorldTransform().getOrigin().x() - m_x0[c];
            sum += std::fabs(d - exact);
            slid += d;
        }
        return {sum / a.copies, 0, fmt("mean_distance_m", slid / a.copies) + fmt("exact_m", exact)};
    }

private:
    std::vector<double> m_x0;
};

// Apex heights of the first kBounces flights after a bounce against r + e^(2k) (y0 - r). An
// apex is extrapolated ballistically from the first falling sample (y + vy^2 / 2g), so the
// 1/60 s sampling does not cap the accuracy; a flight that never happened counts as height r.
class BounceProbe : public Probe {
public:
    static constexpr int kBounces = 3;
    void sample(const AccuracyScene& a, int frame, double) override
    {
        if (frame == 0) m_state.assign(a.copies, Track());
        for (int c = 0; c < a.copies; ++c) {
            const btRigidBody* b = body(a, c, 0);
            const double y = b->getWorldTransform().getOrigin().y(), vy = b->getLinearVelocity().y();
            Track& s = m_state[c];
            if (s.rising && vy <= 0) {
                if (int(s.apex.size()) < kBounces) s.apex.push_back(y + vy * vy / (2 * kG));
                s.rising = false;
            } else if (!s.rising && vy > 0 && frame > 0) s.rising = true;
        }
    }
    Measurement finish(const AccuracyScene& a) override
    {
        const double r = scenes::kBounceRadius, e2 = scenes::kBounceRestitution * scenes::kBounceRestitution;
        double sum = 0, first = 0;
        int missing = 0;
        for (const Track& s : m_state) {
            double exact = scenes::kBounceDropY - r;
            for (int k = 0; k < kBounces; ++k) {
                exact *= e2;
                const double got = k < int(s.apex.size()) ? s.apex[k] : r;
                if (k >= int(s.apex.size())) ++missing;
                sum += std::fabs(got - (r + exact));
                if (k == 0) first += got;
            }
        }
        return {sum / (a.copies * kBounces), 0,
                fmt("first_apex_m", first / a.copies) +
                    fmt("first_apex_exact_m", r + e2 * (scenes::kBounceDropY - r)) + fmt("missing_apexes", missing)};
    }

private:
    struct Track {
        bool rising = false;
        std::vector<double> apex;
    };
    std::vector<Track> m_state;
};

// Angular momentum (world) and rotational kinetic energy, relative drift at the end of the run;
// the error is the larger of the two.
class TumbleProbe : public Probe {
public:
    void sample(const AccuracyScene& a, int frame, double) override
    {
        if (frame == 0)
            for (int c = 0; c < a.copies; ++c) {
                m_l0.push_back(momentum(body(a, c, 0)));
                m_e0.push_back(energy(body(a, c, 0)));
            }
    }
    Measurement finish(const AccuracyScene& a) override
    {
        double dl = 0, de = 0;
        for (int c = 0; c < a.copies; ++c) {
            const btVector3 l = momentum(body(a, c, 0));
            dl += (l - m_l0[c]).length() / m_l0[c].length();
            de += std::fabs(energy(body(a, c, 0)) - m_e0[c]) / m_e0[c];
        }
        dl /= a.copies;
        de /= a.copies;
        return {std::max(dl, de), 0, fmt("momentum_drift", dl) + fmt("energy_drift", de)};
    }

private:
    static btVector3 momentum(const btRigidBody* b)
    {
        const btMatrix3x3& r = b->getWorldTransform().getBasis();
        const btVector3 wLocal = b->getAngularVelocity() * r;  // r^T w
        return r * (b->getLocalInertia() * wLocal);
    }
    static double energy(const btRigidBody* b) { return 0.5 * b->getAngularVelocity().dot(momentum(b)); }
    std::vector<btVector3> m_l0;
    std::vector<double> m_e0;
};

// Mean distance of every box from where it was placed (exactly at rest), at the end; the
// deepest overlap of a resting contact over the whole run (rotation ignored: it stays tiny).
class RestProbe : public Probe {
public:
    void sample(const AccuracyScene& a, int frame, double) override
    {
        const int n = a.copies * a.bodiesPerCopy;
        if (frame == 0)
            for (int i = 0; i < n; ++i) m_p0.push_back(a.scene->body(a.firstBody + i)->getWorldTransform().getOrigin());
        auto y = [&a](int i) { return double(a.scene->body(i)->getWorldTransform().getOrigin().y()); };
        for (const auto& [upper, lower] : a.supports) {
            const double top = lower < 0 ? 0.0 : y(lower) + 0.5;
            m_penetration = std::max(m_penetration, top - (y(upper) - 0.5));
        }
    }
    Measurement finish(const AccuracyScene& a) override
    {
        const int n = a.copies * a.bodiesPerCopy;
        double sum = 0, worst = 0;
        for (int i = 0; i < n; ++i) {
            const double d = (a.scene->body(a.firstBody + i)->getWorldTransform().getOrigin() - m_p0[i]).length();
            sum += d;
            worst = std::max(worst, d);
        }
        return {sum / n, m_penetration, fmt("max_drift_m", worst)};
    }

private:
    std::vector<btVector3> m_p0;
    double m_penetration = 0;
};

// Mean height against the reference, averaged over the samples; kinetic energy and
// penetration compared alongside (notes, penetration column).
class PileProbe : public Probe {
public:
    explicit PileProbe(const PileReference& ref) : m_ref(ref) {}
    void sample(const AccuracyScene& a, int frame, double) override
    {
        const int every = int(kPileSampleSeconds * 60 + 0.5);
        if (frame % every) return;
        std::vector<btRigidBody*> bodies;
        for (int i = 0; i < a.copies * a.bodiesPerCopy; ++i) bodies.push_back(a.scene->body(a.firstBody + i));
        m_rows.push_back(pileStats<btRigidBody, btBoxShape>(bodies));
    }
    Measurement finish(const AccuracyScene&) override
    {
        Measurement m;
        for (const PileStats& s : m_rows) m.penetration = std::max(m.penetration, s.penetration);
        const std::size_t n = std::min(m_rows.size(), m_ref.rows.size());
        if (n == 0) {
            m.error = kNaN;
            m.notes = "no_reference;" + fmt("final_mean_height_m", m_rows.empty() ? kNaN : m_rows.back().meanHeight);
            return m;
        }
        double dh = 0, dk = 0, refPen = 0;
        for (std::size_t i = 0; i < n; ++i) {
            dh += std::fabs(m_rows[i].meanHeight - m_ref.rows[i].meanHeight);
            dk += std::fabs(m_rows[i].kineticEnergy - m_ref.rows[i].kineticEnergy);
            refPen = std::max(refPen, m_ref.rows[i].penetration);
        }
        m.error = dh / n;
        m.notes = fmt("mean_abs_ke_diff_J", dk / n) + fmt("ref_max_penetration_m", refPen) +
                  fmt("final_mean_height_m", m_rows[n - 1].meanHeight) +
                  fmt("ref_final_mean_height_m", m_ref.rows[n - 1].meanHeight);
        return m;
    }

private:
    const PileReference& m_ref;
    std::vector<PileStats> m_rows;
};

}  // namespace

bool readPileReference(const std::string& path, PileReference& out, std::string& why)
{
    std::ifstream in(path);
    if (!in) {
        why = "cannot open " + path;
        return false;
    }
    out = PileReference();
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("# dims", 0) == 0) std::sscanf(line.c_str(), "# dims %d %d %d", &out.dims[0], &out.dims[1], &out.dims[2]);
        else if (line.rfind("# seconds", 0) == 0) std::sscanf(line.c_str(), "# seconds %lf", &out.seconds);
        else if (line.rfind("# settings", 0) == 0) out.settings = line.substr(11);
        else if (!line.empty() && line[0] != '#' && line[0] != 't') {
            PileStats s;
            double t = 0;
            if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &t, &s.meanHeight, &s.penetration, &s.kineticEnergy) == 4)
                out.rows.push_back(s);
        }
    }
    if (out.dims[0] < 1 || out.dims[1] < 1 || out.dims[2] < 1 || out.rows.empty()) {
        why = path + " is not a btgpu_accuracy_reference file";
        return false;
    }
    return true;
}

std::vector<Case> makeCases(bool quick, const PileReference& pile)
{
    using scenes::WorldKind;
    std::vector<Case> cases;
    auto trajectory = [] { return std::make_unique<TrajectoryProbe>(); };
    cases.push_back({"free_fall", "boxes falling from rest, no ground", "position error vs continuous solution (m)",
                     quick ? 1.0 : 2.0, scenes::accuracyFreeFall, trajectory});
    cases.push_back({"projectile", "spheres thrown at (5, 10, 0) m/s, no ground",
                     "position error vs continuous solution (m)", quick ? 1.0 : 2.0, scenes::accuracyProjectile,
                     trajectory});
    cases.push_back({"sliding_box", "box sliding at 5 m/s, friction 0.5: stops after 2.5 m",
                     "stopping distance error (m)", quick ? 1.0 : 1.5, scenes::accuracySlidingBox,
                     [] { return std::make_unique<SlideProbe>(); }});
    cases.push_back({"bouncing_sphere", "sphere dropped from 5 m, restitution 0.5: apexes 1.625, 0.781, 0.570 m",
                     "mean apex height error, 3 bounces (m)", quick ? 3.0 : 3.5, scenes::accuracyBouncingSphere,
                     [] { return std::make_unique<BounceProbe>(); }});
    cases.push_back({"tumbling_box", "box spinning near its intermediate axis, no gravity",
                     "relative drift of angular momentum / energy (1)", quick ? 2.0 : 4.0, scenes::accuracyTumblingBox,
                     [] { return std::make_unique<TumbleProbe>(); }});
    cases.push_back({"stack10", "10 boxes stacked at rest", "mean drift from rest (m)", quick ? 1.5 : 3.0,
                     [](WorldKind k, const Config& c, int copies) {
                         return scenes::accuracyStack(k, c, std::max(1, copies / 10), 10);
                     },
                     [] { return std::make_unique<RestProbe>(); }});
    cases.push_back({"pyramid20", "2-D pyramid of 210 boxes (base 20) at rest", "mean drift from rest (m)",
                     quick ? 1.5 : 3.0,
                     [](WorldKind k, const Config& c, int copies) {
                         return scenes::accuracyPyramid(k, c, std::max(1, copies / 100), 20);
                     },
                     [] { return std::make_unique<RestProbe>(); }});
    int dims[3] = {quick ? 5 : 10, quick ? 4 : 10, quick ? 5 : 10};
    double seconds = quick ? 2.0 : 4.0;
    if (!pile.rows.empty()) {
        std::copy(pile.dims, pile.dims + 3, dims);
        seconds = pile.seconds;
    }
    char desc[128];
    std::snprintf(desc, sizeof desc, "pile of %dx%dx%d boxes vs double-precision reference", dims[0], dims[1],
                  dims[2]);
    cases.push_back({"pile", desc, "mean |mean height - reference| (m)", seconds,
                     [dims](WorldKind k, const Config& c, int) { return scenes::accuracyPile(k, c, dims[0], dims[1], dims[2]); },
                     [&pile] { return std::make_unique<PileProbe>(pile); }});
    return cases;
}

}  // namespace btgpu::accuracy
