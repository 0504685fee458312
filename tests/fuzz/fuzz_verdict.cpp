// fuzz_verdict.cpp — turns the two traces of one recipe into failures. A cluster any of whose
// bodies was given bad input (on either engine) is tainted: none of its bodies is asserted
// finite, since they may touch the bad one. Clusters are far apart, so the rest are.
#include "fuzz_verdict.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <sstream>

namespace btgpu::fuzz {

namespace {

constexpr float kRunawaySpeed = 1e4f;  // m/s: a well-formed body this fast ran away...
constexpr float kStockCalmSpeed = 1e3f;  // ...where stock stayed below this
constexpr float kClosingDv = -0.5f;      // three steps of 1/60 s at g = 10
constexpr float kClosingTol = 0.01f;

std::string bodyName(const Recipe& r, int i)
{
    const BodySpec& b = r.bodies[size_t(i)];
    std::string s = "b" + std::to_string(i) + " (" + r.shapes[size_t(b.shape)].choice;
    if (!b.choice.empty() && b.choice != r.shapes[size_t(b.shape)].choice) s += ", " + b.choice;
    s += b.motion == Motion::Static ? ", static" : b.motion == Motion::Kinematic ? ", kinematic" : "";
    return s + ", cluster C" + std::to_string(b.cluster) + " " + toString(r.clusters[size_t(b.cluster)].role) + ")";
}

std::string callName(const Recipe& r, const Trace& t, int call)
{
    const CallTrace& c = t.calls[size_t(call)];
    if (c.op < 0) return "closing step " + std::to_string(call + 1);
    const Op& op = r.ops[size_t(c.op)];
    std::ostringstream os;
    os << "step " << call + 1 << " (" << op.a << ", " << op.n << ", " << op.b << ")";
    return os.str();
}

}  // namespace

std::vector<Failure> judge(const Recipe& r, const Trace& gpu, const Trace* stock, std::vector<Failure>* notes)
{
    std::vector<Failure> out;
    auto fail = [&](std::string kind, std::string detail) { out.push_back({std::move(kind), std::move(detail)}); };
    auto note = [&](std::string kind, std::string detail) {
        if (notes) notes->push_back({std::move(kind), std::move(detail)});
    };
    for (const std::string& e : gpu.exceptions) fail("exception", e);
    for (const std::string& e : gpu.badIndex) fail("issue-bad-index", e);
    for (const std::string& e : gpu.namedOthers) fail("named-wellformed", "the plane or the closing probe: " + e);

    // What follows a bad stepSimulation call btgpu did not turn away is most likely its doing:
    // such failures carry a suffix, so the root cause stays one class.
    int firstBadCall = int(gpu.calls.size());
    for (size_t k = 0; k < gpu.calls.size(); ++k)
        if (gpu.calls[k].cls == ArgClass::Bad && (gpu.calls[k].returned != 0 || gpu.calls[k].changedBodies)) {
            firstBadCall = int(k);
            break;
        }
    auto after = [&](int call) { return call >= firstBadCall ? std::string("(after bad step arguments)") : std::string(); };

    // A fixed step of microseconds turns Bullet's penetration recovery (erp * depth / dt) into
    // 1e6 m/s on both engines (a 10-box pile at 1e-9 s: stock 2.8e6, btgpu 6.7e6): speeds are
    // only noted then.
    bool tinyStep = false;
    for (const Op& op : r.ops)
        if (op.kind == OpKind::Step && op.n != 0 && op.b > 0.0f && op.b < 1e-4f) tinyStep = true;

    std::set<int> tainted;
    for (size_t i = 0; i < r.bodies.size(); ++i) {
        if (!gpu.bodies[i].badWhy.empty()) tainted.insert(r.bodies[i].cluster);
        if (stock && !stock->bodies[i].badWhy.empty()) tainted.insert(r.bodies[i].cluster);
    }
    for (size_t i = 0; i < r.bodies.size(); ++i) {
        const BodyTrace& g = gpu.bodies[i];
        if (!g.built) continue;
        const Role role = r.clusters[size_t(r.bodies[i].cluster)].role;
        const bool wellFormed = g.badWhy.empty() && !tainted.count(r.bodies[i].cluster);
        const BodyTrace* s = stock && stock->bodies[i].built ? &stock->bodies[i] : nullptr;
        const std::string name = bodyName(r, int(i));
        // Asserted where stock keeps the body finite (a normal body also where stock did not
        // get the scene's bad bodies); where stock goes NaN too it is only noted.
        if (wellFormed && g.nonFiniteAtCall >= 0) {
            std::string when = "non-finite after " + callName(r, gpu, g.nonFiniteAtCall);
            if (s && s->nonFiniteAtCall >= 0) note("nan-like-stock(" + std::string(toString(role)) + ")", name + ": " + when + ", as on stock");
            else if (role != Role::Extreme) fail("nan-wellformed" + after(g.nonFiniteAtCall), name + ": " + when);
            else if (s) fail("nan-extreme" + after(g.nonFiniteAtCall), name + ": " + when + "; stock stays finite");
        }
        if (!g.badWhy.empty() && g.mustBeNamed && !g.named)
            fail("unnamed-bad(" + g.mustPath + ": " + g.badWhy + ")",
                 name + ": bad " + g.badWhy + " from " + callName(r, gpu, g.badAtCall) + ", no BadBody issue with its index");
        // Naming a body that had already gone non-finite is right; the NaN is the failure (or
        // shared with stock).
        const bool nanFirst = g.nonFiniteAtCall >= 0 && g.nonFiniteAtCall < g.namedAtCall;
        // A body that ran away at a microsecond step may rightly be disabled for its AABB.
        if (wellFormed && g.named && role != Role::Extreme && !nanFirst && tinyStep && g.maxSpeed > kRunawaySpeed)
            note("named-after-tiny-fixed-step", name + ": " + g.namedBy);
        else if (wellFormed && g.named && role != Role::Extreme && !nanFirst)
            fail("named-wellformed" + after(g.namedAtCall), name + ": " + g.namedBy);
        if (wellFormed && role == Role::Normal && g.maxSpeed > kRunawaySpeed && (!s || s->maxSpeed < kStockCalmSpeed)) {
            std::ostringstream os;
            os << name << ": " << g.maxSpeed << " m/s (stock " << (s ? s->maxSpeed : -1.0f) << ")";
            if (tinyStep) note("runaway-with-tiny-fixed-step", os.str());
            else fail("runaway" + after(g.maxSpeedAtCall), os.str());
        }
    }

    // Calls. Substeps are compared with stock's while both have kept the same time; an
    // ambiguous call btgpu reported as bad ends the comparison (stock took Bullet's meaning).
    bool sameTime = stock != nullptr;
    // The same bad call again right after one that was reported need not be reported again (an
    // app stuck on dt = NaN would flood the issues).
    auto repeat = [&](size_t k) {
        const CallTrace &a = gpu.calls[k], &b = gpu.calls[k - 1];
        return std::memcmp(&a.dt, &b.dt, sizeof(float)) == 0 && a.maxSubSteps == b.maxSubSteps &&
               std::memcmp(&a.fixedStep, &b.fixedStep, sizeof(float)) == 0;
    };
    std::vector<bool> reported(gpu.calls.size(), false);
    for (size_t k = 0; k < gpu.calls.size(); ++k) {
        const CallTrace& c = gpu.calls[k];
        reported[k] = c.reported || (k > 0 && reported[k - 1] && repeat(k));
        if (c.cls == ArgClass::Bad) {
            if (c.returned != 0) fail("bad-args-simulated", callName(r, gpu, int(k)) + " returned " + std::to_string(c.returned));
            if (c.changedBodies) fail("bad-args-moved-bodies", callName(r, gpu, int(k)) + " changed a body or motion state");
            if (!reported[k]) fail("bad-args-unreported", callName(r, gpu, int(k)) + " added no issue naming the argument");
            continue;
        }
        if (c.cls == ArgClass::Ambiguous && reported[k]) {
            if (c.changedBodies) fail("bad-args-moved-bodies", callName(r, gpu, int(k)) + " reported bad yet changed bodies");
            sameTime = false;
            continue;
        }
        if (sameTime && k < stock->calls.size() && stock->calls[k].ran && c.returned != stock->calls[k].returned)
            fail("substeps-differ" + after(int(k)), callName(r, gpu, int(k)) + " returned " + std::to_string(c.returned) +
                                                        ", stock " + std::to_string(stock->calls[k].returned));
    }

    // On the CPU path btgpu is the base class: with the same input it must match stock bitwise
    // (a world that changes the app's shapes, say, no longer does).
    bool sameInput = stock && !gpu.calls.empty();
    for (size_t i = 0; sameInput && i < r.bodies.size(); ++i)
        sameInput = stock->bodies[i].built && gpu.bodies[i].badWhy.empty() && stock->bodies[i].badWhy.empty();
    for (const Op& op : r.ops) sameInput = sameInput && op.stockSafe;
    for (const CallTrace& c : gpu.calls) sameInput = sameInput && c.gpuPath == "cpu";
    // Until a body goes non-finite: from then on btgpu holds it out (named) where stock keeps it.
    size_t firstNan = gpu.calls.size();
    for (size_t i = 0; sameInput && i < r.bodies.size(); ++i)
        for (int c : {gpu.bodies[i].nonFiniteAtCall, stock ? stock->bodies[i].nonFiniteAtCall : -1})
            if (c >= 0) firstNan = std::min(firstNan, size_t(c));
    if (sameInput)
        for (size_t k = 0; k < firstNan && k < stock->calls.size(); ++k)
            if (gpu.calls[k].stateHash != stock->calls[k].stateHash) {
                fail("cpu-path-differs-from-stock", "bodies differ bitwise from stock's after " + callName(r, gpu, int(k)) +
                                                        " (CPU path all along, same input)");
                break;
            }

    if (!gpu.probeFinite && stock && !stock->probeFinite) note("nan-like-stock(probe)", "the probe went non-finite, as on stock");
    else if (!gpu.probeFinite) fail("probe-nan", "the free-falling probe went non-finite");
    else if (std::fabs(gpu.probeDv - kClosingDv) > kClosingTol)
        fail("probe-stopped", "probe's vy changed by " + std::to_string(gpu.probeDv) + " over the closing steps, not -0.5");
    // Config::internalSubsteps > 1 integrates in shorter steps, and so do the soft step's
    // substeps: the same velocity, not the same position as stock's.
    if (sameTime && r.internalSubsteps == 1 && !r.soft && gpu.probeFinite && stock->probeFinite) {
        float d = (gpu.probePos - stock->probePos).length();
        if (d > 1e-3f * (1.0f + stock->probePos.length() * 1e-3f))
            fail("probe-differs" + after(int(gpu.calls.size()) - 3), "probe " + std::to_string(d) + " m from stock's after the recipe");
    }
    if (!gpu.lateProbeFinite && stock && !stock->lateProbeFinite) note("nan-like-stock(probe)", "the closing sphere went non-finite, as on stock");
    else if (!gpu.lateProbeFinite) fail("late-probe-nan", "a sphere added at the end went non-finite");
    else if (std::fabs(gpu.lateProbeDv - kClosingDv) > kClosingTol)
        fail("late-probe-stopped", "a sphere added at the end: vy changed by " + std::to_string(gpu.lateProbeDv));
    return out;
}

std::vector<std::string> stockNotes(const Recipe& r, const Trace& stock)
{
    std::vector<std::string> out;
    std::set<int> tainted;
    for (size_t i = 0; i < r.bodies.size(); ++i)
        if (!stock.bodies[i].badWhy.empty()) tainted.insert(r.bodies[i].cluster);
    for (size_t i = 0; i < r.bodies.size(); ++i) {
        const BodyTrace& s = stock.bodies[i];
        if (!s.built || !s.badWhy.empty() || tainted.count(r.bodies[i].cluster) || s.nonFiniteAtCall < 0) continue;
        out.push_back("stock-nan(" + std::string(toString(r.clusters[size_t(r.bodies[i].cluster)].role)) + ") " +
                      bodyName(r, int(i)) + " after " + callName(r, stock, s.nonFiniteAtCall));
    }
    for (const std::string& e : stock.exceptions) out.push_back("stock-exception " + e);
    return out;
}

std::string dump(const Recipe& r, const Trace& t)
{
    std::ostringstream os;
    for (size_t i = 0; i < r.bodies.size(); ++i) {
        const BodyTrace& b = t.bodies[i];
        if (!b.built) {
            os << "    " << bodyName(r, int(i)) << ": not built\n";
            continue;
        }
        os << "    " << bodyName(r, int(i)) << ":";
        if (!b.badWhy.empty()) os << " bad " << b.badWhy << " from call " << b.badAtCall + 1 << (b.mustBeNamed ? " (must be named)" : "");
        if (b.named) os << " named \"" << b.namedBy << "\"";
        if (b.nonFiniteAtCall >= 0) os << " non-finite after call " << b.nonFiniteAtCall + 1;
        os << " max speed " << b.maxSpeed << "\n";
    }
    for (size_t k = 0; k < t.calls.size(); ++k) {
        const CallTrace& c = t.calls[k];
        os << "    call " << k + 1 << " " << toString(c.cls) << (c.ran ? "" : " (not run)") << " returned " << c.returned
           << (c.changedBodies ? " changed bodies" : "") << (c.reported ? " reported" : "") << " " << c.gpuPath << "\n";
    }
    os << "    probe at (" << t.probePos.x() << ", " << t.probePos.y() << ", " << t.probePos.z() << "), dv " << t.probeDv << ", late probe dv " << t.lateProbeDv << ", issues " << t.issues;
    if (!t.cpuReason.empty()) os << ", CPU path: " << t.cpuReason;
    for (const std::string& e : t.exceptions) os << "\n    exception " << e;
    return os.str() + "\n";
}

}  // namespace btgpu::fuzz
