// fuzz_recipe.cpp — the seeded generator: clusters of bodies far enough apart that nothing
// crosses from one to another in a short scene, then a timeline of app actions between steps.
// Its own RNG (splitmix64) so a seed means the same scene with any standard library.
#include "fuzz_recipe.h"

#include <algorithm>
#include <cfloat>
#include <climits>
#include <cmath>
#include <limits>

namespace btgpu::fuzz {

namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kStep = 1.0f / 60.0f;
constexpr int kMaxSubstepsPerCall = 60;  // the generator never asks for more (bounded run time)

class Rng {
public:
    explicit Rng(std::uint64_t seed) : m_state(seed) {}
    std::uint64_t next()
    {
        std::uint64_t z = (m_state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }
    float range(double a, double b) { return float(a + (b - a) * uniform()); }
    int below(int n) { return int(next() % std::uint64_t(n)); }
    int between(int a, int b) { return a + below(b - a + 1); }  // inclusive
    bool chance(double p) { return uniform() < p; }
    float logUniform(double a, double b) { return float(std::exp(std::log(a) + (std::log(b) - std::log(a)) * uniform())); }
    template <class T>
    const T& pick(const std::vector<T>& v) { return v[size_t(below(int(v.size())))]; }
    btVector3 vec(double a, double b) { return btVector3(range(a, b), range(a, b), range(a, b)); }

private:
    std::uint64_t m_state;
};

float badScalar(Rng& rng)
{
    int k = rng.below(4);
    return k < 2 ? kNan : (k == 2 ? kInf : -kInf);
}

// A plausible vector with one to three components replaced by NaN or +-Inf.
btVector3 badVec(Rng& rng, double scale)
{
    btVector3 v = rng.vec(-scale, scale);
    int count = rng.between(1, 3);
    for (int i = 0; i < count; ++i) v[rng.below(3)] = badScalar(rng);
    return v;
}

float boundingRadius(const ShapeSpec& s)
{
    // A bad shape's NaN or Inf must not move the clusters placed after it.
    if (!std::isfinite(s.size.length())) return 1.0f;
    switch (s.kind) {
        case ShapeKind::Box: return s.size.length();
        case ShapeKind::Sphere: return s.size.x();
        case ShapeKind::Hull: {
            float r = 0.05f;
            for (const btVector3& p : s.points)
                if (std::isfinite(p.length())) r = std::max(r, p.length() + 0.04f);
            return r;
        }
        case ShapeKind::Capsule: case ShapeKind::Cone: return s.size.x() + 0.5f * s.size.y();
        case ShapeKind::Cylinder: return s.size.length();
        case ShapeKind::Compound: return s.size.length() + 1.0f;
        case ShapeKind::Plane: return 0.0f;
    }
    return 1.0f;
}

class Generator {
public:
    Generator(std::uint64_t seed, Profile profile, const Skip& skip)
        : m_rng(seed * 0x2545f4914f6cdd1dull + std::uint64_t(profile) * 0x9e3779b97f4a7c15ull + 1), m_skip(skip)
    {
        m_r.seed = seed;
        m_r.profile = profile;
    }

    Recipe make()
    {
        Profile p = m_r.profile;
        m_r.groundPlane = m_rng.chance(0.6);
        if (m_r.groundPlane && m_rng.chance(0.3)) {
            // Tilted about x only: every cluster sits on z = 0, where the plane stays at y = 0.
            float t = m_rng.range(-0.25, 0.25);
            m_r.planeNormal = btVector3(0, std::cos(t), std::sin(t));
        }
        std::vector<Role> roles;
        int normals = m_rng.between(1, 2);
        for (int i = 0; i < normals; ++i) roles.push_back(Role::Normal);
        if (p == Profile::BadBodies || p == Profile::CpuPath || p == Profile::BadShapes) {
            int bad = m_rng.between(1, 3);
            for (int i = 0; i < bad; ++i) roles.push_back(Role::Bad);
        }
        if (p == Profile::StepArguments && m_rng.chance(0.4)) roles.push_back(Role::Bad);
        if (p == Profile::Extreme) {
            int extreme = m_rng.between(1, 3);
            for (int i = 0; i < extreme; ++i) roles.push_back(Role::Extreme);
        }
        // Bad and normal clusters interleaved; extreme ones last, the largest furthest out, so
        // a 1e6 m box does not push everything else to coordinates where floats are coarse.
        for (size_t i = roles.size(); i > 1; --i) {
            size_t j = size_t(m_rng.below(int(i)));
            if (roles[i - 1] != Role::Extreme && roles[j] != Role::Extreme) std::swap(roles[i - 1], roles[j]);
        }
        bool unsupportedDone = p != Profile::CpuPath;
        for (Role role : roles) {
            int c = makeCluster(role);
            if (!unsupportedDone && role == Role::Normal) unsupportedDone = addUnsupported(c);
        }
        if (!unsupportedDone) addUnsupported(makeCluster(Role::Normal));
        makeProbe();
        place();
        makeTimeline();
        // Last, so a scene's bodies and ops do not depend on them.
        m_r.internalSubsteps = m_rng.chance(0.8) ? 1 : m_rng.pick(std::vector<int>{2, 4});
        m_r.jacobi = m_rng.chance(0.15);
        m_r.profiling = m_rng.chance(0.15);
        m_r.syncAabbs = m_rng.chance(0.85);
        // the library's default solver (Auto: the soft step) in half the scenes without Jacobi;
        // drawn last, so every earlier draw is what it was before it existed
        m_r.soft = !m_r.jacobi && m_rng.chance(0.5);
        return m_r;
    }

private:
    int addShape(ShapeSpec s)
    {
        m_r.shapes.push_back(std::move(s));
        return int(m_r.shapes.size()) - 1;
    }

    ShapeSpec normalShape()
    {
        ShapeSpec s;
        int k = m_rng.below(10);
        if (k < 4) {
            s.kind = ShapeKind::Box;
            s.size = m_rng.vec(0.1, 1.2);
            s.choice = "box";
        } else if (k < 7) {
            s.kind = ShapeKind::Sphere;
            s.size = btVector3(m_rng.range(0.1, 1.0), 0, 0);
            s.choice = "sphere";
        } else if (k < 9) {
            s.kind = ShapeKind::Hull;
            int n = m_rng.between(5, 16);
            float extent = m_rng.range(0.2, 1.2);
            for (int i = 0; i < n; ++i) s.points.push_back(m_rng.vec(-extent, extent));
            s.choice = "hull-random";
        } else {
            // Box corners, each given twice, and an interior point: a proper hull from duplicates.
            s.kind = ShapeKind::Hull;
            btVector3 h = m_rng.vec(0.2, 1.0);
            for (int i = 0; i < 8; ++i) {
                btVector3 c((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
                s.points.push_back(c);
                s.points.push_back(c);
            }
            s.points.push_back(btVector3(0, 0, 0));
            s.choice = "hull-duplicates";
        }
        return s;
    }

    // What a skipped choice becomes: drawn after the choice's own random numbers, so that
    // BTGPU_FUZZ_SKIP changes nothing else in the scene.
    ShapeSpec plainBox(const std::string& skipped)
    {
        ShapeSpec s;
        s.kind = ShapeKind::Box;
        s.size = btVector3(0.5f, 0.5f, 0.5f);
        s.choice = "box(" + skipped + " skipped)";
        return s;
    }

    // The finite but odd: extreme sizes and aspect ratios, degenerate hulls.
    ShapeSpec extremeShape(std::string* choice)
    {
        static const std::vector<std::string> sizes = {"size-huge", "size-tiny", "size-plank", "sphere-huge", "sphere-tiny"};
        // Degenerate hulls send the world to the CPU path: rarely, so most scenes test the GPU's.
        static const std::vector<std::string> degenerate = {"hull-coplanar", "hull-one-point", "hull-few",
                                                            "hull-collinear", "hull-same-point", "hull-tiny"};
        ShapeSpec s;
        *choice = m_rng.chance(0.85) ? m_rng.pick(sizes) : m_rng.pick(degenerate);
        const std::string& c = *choice;
        s.choice = c;
        if (c == "size-huge") {
            s.kind = ShapeKind::Box;
            s.size = btVector3(m_rng.logUniform(1e3, 1e6), m_rng.logUniform(1e3, 1e6), m_rng.logUniform(1e3, 1e6));
        } else if (c == "size-tiny") {
            s.kind = ShapeKind::Box;
            s.size = btVector3(m_rng.logUniform(1e-6, 1e-3), m_rng.logUniform(1e-6, 1e-3), m_rng.logUniform(1e-6, 1e-3));
        } else if (c == "size-plank") {
            s.kind = ShapeKind::Box;
            s.size = btVector3(m_rng.logUniform(1, 1e4), m_rng.logUniform(1e-6, 1e-3), m_rng.logUniform(1, 1e4));
        } else if (c == "sphere-huge") {
            s.kind = ShapeKind::Sphere;
            s.size = btVector3(m_rng.logUniform(1e3, 1e6), 0, 0);
        } else if (c == "sphere-tiny") {
            s.kind = ShapeKind::Sphere;
            s.size = btVector3(m_rng.logUniform(1e-6, 1e-3), 0, 0);
        } else {
            s.kind = ShapeKind::Hull;
            int n = c == "hull-one-point" ? 1 : c == "hull-few" ? m_rng.between(2, 3) : m_rng.between(3, 10);
            float extent = m_rng.range(0.2, 1.0);
            btVector3 same = m_rng.vec(-extent, extent), dir = m_rng.vec(-1, 1);
            for (int i = 0; i < n; ++i) {
                btVector3 q = m_rng.vec(-extent, extent);
                if (c == "hull-coplanar") q.setY(0);
                if (c == "hull-collinear") q = dir * m_rng.range(-extent, extent);
                if (c == "hull-same-point") q = same;
                if (c == "hull-tiny") q = m_rng.vec(-1e-6, 1e-6);
                s.points.push_back(q);
            }
        }
        if (m_skip.has(c)) s = plainBox(c), *choice = s.choice;
        return s;
    }

    // A shape that is bad from the start (BadShapes): NaN or Inf in its parameters, or a hull
    // without points (stock Bullet segfaults in GJK when one touches anything).
    ShapeSpec badShape(std::string* choice)
    {
        static const std::vector<std::string> kinds = {"hull-nan-point", "hull-inf-point", "box-nan-extent",
                                                       "sphere-nan-radius", "hull-empty"};
        ShapeSpec s = normalShape();
        *choice = m_rng.pick(kinds);
        const std::string& c = *choice;
        s.choice = c;
        if (c == "hull-nan-point" || c == "hull-inf-point") {
            s.kind = ShapeKind::Hull;
            s.points.clear();
            for (int i = 0; i < 8; ++i) s.points.push_back(m_rng.vec(-0.5, 0.5));
            s.points[size_t(m_rng.below(8))][m_rng.below(3)] = c == "hull-nan-point" ? kNan : kInf;
        } else if (c == "box-nan-extent") {
            s.kind = ShapeKind::Box;
            s.size = m_rng.vec(0.2, 1.0);
            s.size[m_rng.below(3)] = kNan;
        } else if (c == "sphere-nan-radius") {
            s.kind = ShapeKind::Sphere;
            s.size = btVector3(m_rng.chance(0.5) ? kNan : kInf, 0, 0);
        } else {
            s.kind = ShapeKind::Hull;
            s.points.clear();
        }
        if (m_skip.has(c)) s = plainBox(c), *choice = s.choice;
        return s;
    }

    int makeCluster(Role role)
    {
        ClusterSpec cl;
        cl.role = role;
        int c = int(m_r.clusters.size());
        int count = 1;
        if (role == Role::Normal) {
            bool pile = m_rng.chance(0.3);
            cl.layout = pile ? "pile" : (m_rng.chance(0.5) ? "stack" : "scatter");
            count = pile ? m_rng.between(4, 20) : m_rng.between(1, 6);
        } else if (role == Role::Bad) {
            cl.layout = m_rng.pick(std::vector<std::string>{"pile", "stack", "scatter"});
            count = m_rng.between(1, 5);
        } else {
            cl.layout = m_rng.chance(0.6) ? "single" : "stack";
            count = cl.layout == "single" ? 1 : m_rng.between(2, 3);
        }
        cl.ground = !m_r.groundPlane || m_rng.chance(0.3);
        m_r.clusters.push_back(cl);
        // One shape shared by the whole cluster now and then: the shape tables must dedupe.
        int shared = role != Role::Extreme && m_rng.chance(0.2) ? addShape(normalShape()) : -1;
        for (int i = 0; i < count; ++i) {
            BodySpec b;
            b.cluster = c;
            b.friction = m_rng.chance(0.7) ? 0.5f : m_rng.range(0.0, 1.5);
            b.restitution = m_rng.chance(0.7) ? 0.0f : m_rng.range(0.0, 0.9);
            b.mass = m_rng.range(0.2, 10.0);
            if (role == Role::Extreme && i > 0 && m_rng.chance(0.3)) {
                // A usual body on or under an extreme one: the pair is where sizes meet.
                b.shape = addShape(normalShape());
            } else if (role == Role::Extreme) {
                std::string choice;
                b.shape = addShape(extremeShape(&choice));
                b.choice = choice;
                int k = m_rng.below(6);
                if (k == 0) b.mass = 1e-6f, b.choice += "+mass-tiny";
                if (k == 1) b.mass = 1e6f, b.choice += "+mass-huge";
                if (k == 2 && cl.layout == "stack") b.mass = i == 0 ? 1e6f : 1e-3f, b.choice += "+mass-ratio";
            } else if (role == Role::Bad && m_r.profile == Profile::BadShapes && m_rng.chance(0.6)) {
                std::string choice;
                b.shape = addShape(badShape(&choice));
                b.choice = choice;
                b.stockSafe = choice != "hull-empty";
            } else {
                b.shape = shared >= 0 && m_rng.chance(0.8) ? shared : addShape(normalShape());
            }
            if (m_rng.chance(0.1)) b.motion = Motion::Static, b.mass = 0;
            else if (m_rng.chance(0.08)) b.motion = Motion::Kinematic, b.mass = 0;
            if (role != Role::Extreme && m_rng.chance(0.3)) b.linVel = m_rng.vec(-2, 2);
            if (role != Role::Extreme && m_rng.chance(0.3)) b.angVel = m_rng.vec(-3, 3);
            if (m_rng.chance(0.3)) {
                btQuaternion q(m_rng.range(-1, 1), m_rng.range(-1, 1), m_rng.range(-1, 1), m_rng.range(0.1, 1));
                b.start.setRotation(q.normalized());
            }
            if (role == Role::Bad && m_r.profile == Profile::BadBodies && m_rng.chance(0.1)) {
                // Bad from the first step: the body is built with a NaN velocity.
                btVector3 v = badVec(m_rng, 2);
                if (!m_skip.has("bad-start")) b.linVel = v, b.choice = "bad-start";
            }
            b.atStart = m_rng.chance(0.85);
            m_r.bodies.push_back(b);
        }
        if (cl.ground) {
            BodySpec g;
            g.cluster = c;
            g.motion = Motion::Static;
            g.mass = 0;
            ShapeSpec box;
            box.kind = ShapeKind::Box;
            box.choice = "ground-box";
            g.shape = addShape(box);  // sized in place(), once the cluster's extent is known
            g.choice = "ground";
            m_r.bodies.push_back(g);
        }
        return c;
    }

    bool addUnsupported(int c)
    {
        static const std::vector<std::string> kinds = {"capsule", "cylinder", "cone", "compound"};
        ShapeSpec s;
        s.choice = m_rng.pick(kinds);
        s.kind = s.choice == "capsule" ? ShapeKind::Capsule
               : s.choice == "cylinder" ? ShapeKind::Cylinder
               : s.choice == "cone" ? ShapeKind::Cone : ShapeKind::Compound;
        s.size = btVector3(m_rng.range(0.2, 0.6), m_rng.range(0.4, 1.5), m_rng.range(0.2, 0.6));
        if (m_skip.has(s.choice)) s = plainBox(s.choice);
        BodySpec b;
        b.cluster = c;
        b.shape = addShape(s);
        b.mass = m_rng.range(0.5, 5.0);
        m_r.bodies.push_back(b);
        return true;
    }

    void makeProbe()
    {
        ClusterSpec cl;
        cl.role = Role::Probe;
        cl.layout = "single";
        m_r.clusters.push_back(cl);
        ShapeSpec s;
        s.kind = ShapeKind::Sphere;
        s.size = btVector3(0.5f, 0, 0);
        s.choice = "probe";
        BodySpec b;
        b.cluster = int(m_r.clusters.size()) - 1;
        b.shape = addShape(s);
        b.ownGravity = true;
        b.choice = "probe";
        m_r.bodies.push_back(b);
        m_r.probe = int(m_r.bodies.size()) - 1;
    }

    // Local positions per layout, then clusters along x, each beyond the last by a gap that
    // nothing in a scene of at most a few simulated seconds crosses.
    void place()
    {
        float x = 0.0f, lastRadius = 0.0f;
        for (size_t c = 0; c < m_r.clusters.size(); ++c) {
            ClusterSpec& cl = m_r.clusters[c];
            float height = 0.0f, radius = 1.0f, pileY = 0.0f;
            for (const BodySpec& b : m_r.bodies)
                if (b.cluster == int(c) && b.choice != "ground") pileY = std::max(pileY, boundingRadius(m_r.shapes[size_t(b.shape)]));
            for (BodySpec& b : m_r.bodies) {
                if (b.cluster != int(c) || b.choice == "ground") continue;
                float r = boundingRadius(m_r.shapes[size_t(b.shape)]);
                btVector3 p(0, 0, 0);
                if (cl.role == Role::Probe) p = btVector3(0, 1000, 0);  // free fall for the whole scene
                else if (cl.layout == "pile") p = btVector3(0, pileY + 0.5f, 0);
                else if (cl.layout == "stack") {
                    p = btVector3(m_rng.range(-0.05, 0.05), height + r + 0.01f, m_rng.range(-0.05, 0.05));
                    height += 2.0f * r + 0.01f;
                } else if (cl.layout == "scatter") p = btVector3(m_rng.range(-3, 3), r + m_rng.range(0.0, 3.0), m_rng.range(-3, 3));
                else p = btVector3(0, r + 0.5f, 0);
                b.start.setOrigin(p);
                radius = std::max(radius, btVector3(p.x(), 0, p.z()).length() + r);
            }
            cl.radius = radius;
            float gap = 100.0f + 0.1f * std::max(radius, lastRadius);
            x += (c == 0 ? 0.0f : lastRadius + gap + radius);
            cl.centre = btVector3(x, 0, 0);
            lastRadius = radius;
            for (BodySpec& b : m_r.bodies) {
                if (b.cluster != int(c)) continue;
                if (b.choice == "ground") {
                    m_r.shapes[size_t(b.shape)].size = btVector3(radius + 2.0f, 1.0f, radius + 2.0f);
                    b.start.setOrigin(btVector3(0, -1, 0));
                }
                b.start.setOrigin(b.start.getOrigin() + cl.centre);
            }
        }
        m_r.farX = x + lastRadius + 200.0f;
    }

    // --- the timeline ---------------------------------------------------------------------

    std::vector<int> bodiesIn(Role role, bool dynamicOnly)
    {
        std::vector<int> out;
        for (size_t i = 0; i < m_r.bodies.size(); ++i) {
            const BodySpec& b = m_r.bodies[i];
            if (m_r.clusters[size_t(b.cluster)].role != role) continue;
            if (dynamicOnly && b.motion != Motion::Dynamic) continue;
            out.push_back(int(i));
        }
        return out;
    }

    void push(Op op)
    {
        if (!op.choice.empty() && m_skip.has(op.choice)) return;
        m_r.ops.push_back(std::move(op));
    }

    Op bodyOp(OpKind kind, int body, const std::string& choice)
    {
        Op op;
        op.kind = kind;
        op.body = body;
        op.choice = choice;
        return op;
    }

    void badOp(int body)
    {
        static const std::vector<std::string> kinds = {
            "bad-linvel",   "bad-angvel",      "bad-teleport", "bad-basis",     "bad-force",    "bad-torque",
            "bad-gravity",  "bad-damping",     "bad-friction", "bad-restitution", "bad-linfactor", "bad-angfactor",
            "bad-sleeping", "bad-mass",        "bad-inertia",  "bad-scaling",   "bad-margin"};
        const BodySpec& b = m_r.bodies[size_t(body)];
        std::string c = m_rng.pick(kinds);
        if (m_r.profile == Profile::BadShapes) c = m_rng.chance(0.5) ? "bad-scaling" : "bad-margin";
        if (b.motion == Motion::Kinematic) c = "bad-kinematic";
        else if (b.motion == Motion::Static && c != "bad-basis") c = "bad-teleport";
        Op op = bodyOp(OpKind::LinVel, body, c);
        if (c == "bad-linvel") op.kind = OpKind::LinVel, op.v = badVec(m_rng, 3);
        if (c == "bad-angvel") op.kind = OpKind::AngVel, op.v = badVec(m_rng, 3);
        if (c == "bad-teleport") op.kind = OpKind::Teleport, op.v = badVec(m_rng, 5), op.a = 1.0f;
        if (c == "bad-basis") op.kind = OpKind::Teleport, op.v = b.start.getOrigin(), op.a = badScalar(m_rng);
        if (c == "bad-force") op.kind = OpKind::Force, op.v = badVec(m_rng, 10);
        if (c == "bad-torque") op.kind = OpKind::Torque, op.v = badVec(m_rng, 10);
        if (c == "bad-gravity") op.kind = OpKind::BodyGravity, op.v = badVec(m_rng, 10);
        // Bullet clamps damping into [0, 1], which turns Inf into 1: only NaN stays bad.
        if (c == "bad-damping") {
            op.kind = OpKind::Damping;
            bool linear = m_rng.chance(0.5);
            op.a = linear ? kNan : 0.1f;
            op.b = linear ? 0.1f : kNan;
        }
        if (c == "bad-friction") op.kind = OpKind::Friction, op.a = badScalar(m_rng);
        if (c == "bad-restitution") op.kind = OpKind::Restitution, op.a = badScalar(m_rng);
        if (c == "bad-linfactor") op.kind = OpKind::LinFactor, op.v = badVec(m_rng, 1);
        if (c == "bad-angfactor") op.kind = OpKind::AngFactor, op.v = badVec(m_rng, 1);
        if (c == "bad-sleeping") op.kind = OpKind::Sleeping, op.a = kNan, op.b = m_rng.chance(0.5) ? kNan : 1.0f;
        if (c == "bad-mass") {
            op.kind = OpKind::MassProps;
            int k = m_rng.below(3);
            op.a = k == 0 ? kNan : (k == 1 ? kInf : -1.0f);
            op.n = 1;  // inertia from the shape for this mass
        }
        if (c == "bad-inertia") op.kind = OpKind::MassProps, op.a = 1.0f, op.v = badVec(m_rng, 1), op.n = 0;
        if (c == "bad-scaling") op.kind = OpKind::Scaling, op.v = badVec(m_rng, 1.5);
        if (c == "bad-margin") op.kind = OpKind::Margin, op.a = badScalar(m_rng);
        if (c == "bad-kinematic") op.kind = OpKind::MoveKinematic, op.v = badVec(m_rng, 5);
        push(op);
    }

    void extremeOp(int body)
    {
        static const std::vector<std::string> kinds = {"spin",        "speed",      "friction-huge", "restitution-huge",
                                                       "sleep-inf",   "scale-zero", "scale-up",      "scale-down",
                                                       "margin-zero", "margin-big", "mass-huge",     "damping-one"};
        std::string c = m_rng.pick(kinds);
        // Ten times a body larger than a few metres would reach the next cluster.
        if (c == "scale-up" && boundingRadius(m_r.shapes[size_t(m_r.bodies[size_t(body)].shape)]) > 5.0f) c = "scale-down";
        Op op = bodyOp(OpKind::AngVel, body, c);
        if (c == "spin") op.kind = OpKind::AngVel, op.v = btVector3(m_rng.range(-1, 1), 1, m_rng.range(-1, 1)).normalized() * 1e22f;
        // Straight up or down: gone from every cluster within one step.
        if (c == "speed") op.kind = OpKind::LinVel, op.v = btVector3(0, m_rng.chance(0.5) ? 1e20f : -1e20f, 0);
        if (c == "friction-huge") op.kind = OpKind::Friction, op.a = 1e10f;
        if (c == "restitution-huge") op.kind = OpKind::Restitution, op.a = 10.0f;
        if (c == "sleep-inf") op.kind = OpKind::Sleeping, op.a = kInf, op.b = kInf;
        if (c == "scale-zero") op.kind = OpKind::Scaling, op.v = btVector3(0, 0, 0);
        if (c == "scale-up") op.kind = OpKind::Scaling, op.v = btVector3(10, 10, 10);
        if (c == "scale-down") op.kind = OpKind::Scaling, op.v = btVector3(1e-4f, 1e-4f, 1e-4f);
        if (c == "margin-zero") op.kind = OpKind::Margin, op.a = 0.0f;
        if (c == "margin-big") op.kind = OpKind::Margin, op.a = 2.0f;
        if (c == "mass-huge") op.kind = OpKind::MassProps, op.a = 1e6f, op.n = 1;
        if (c == "damping-one") op.kind = OpKind::Damping, op.a = 1.0f, op.b = 1.0f;
        push(op);
    }

    // A finite change an app makes every day: the world must pick it up, nothing more.
    void goodOp(int body)
    {
        const BodySpec& b = m_r.bodies[size_t(body)];
        const btVector3 home = m_r.clusters[size_t(b.cluster)].centre;
        if (b.motion == Motion::Kinematic) {
            push([&] { Op op = bodyOp(OpKind::MoveKinematic, body, "move-kinematic");
                       op.v = b.start.getOrigin() + m_rng.vec(-0.2, 0.2); return op; }());
            return;
        }
        if (b.motion == Motion::Static) return;
        int k = m_rng.below(6);
        Op op = bodyOp(OpKind::LinVel, body, "");
        if (k == 0) op.kind = OpKind::LinVel, op.v = m_rng.vec(-3, 3), op.choice = "set-linvel";
        if (k == 1) op.kind = OpKind::AngVel, op.v = m_rng.vec(-5, 5), op.choice = "set-angvel";
        if (k == 2) op.kind = OpKind::Teleport, op.v = home + btVector3(m_rng.range(-1, 1), 4, m_rng.range(-1, 1)), op.a = 1.0f, op.choice = "teleport";
        if (k == 3) op.kind = OpKind::Force, op.v = m_rng.vec(-50, 50), op.choice = "force";
        if (k == 4) op.kind = OpKind::Friction, op.a = m_rng.range(0, 1), op.choice = "friction";
        if (k == 5) op.kind = OpKind::MassProps, op.a = m_rng.range(0.5, 5), op.n = 1, op.choice = "mass";
        push(op);
    }

    void stepOp(float* localTime, bool odd)
    {
        for (int attempt = 0;; ++attempt) {
            Op op;
            op.kind = OpKind::Step;
            op.a = kStep, op.n = 1, op.b = kStep;
            if (!odd || attempt > 20) {
                int k = m_rng.below(10);
                if (k == 7) op.a = 2 * kStep, op.n = 2;
                if (k == 8) op.a = 0.5f * kStep;
                if (k == 9) op.n = 0;  // variable step
            } else {
                op.a = m_rng.pick(std::vector<float>{0.0f, -kStep, 1e30f, kInf, -kInf, kNan, kStep, 2 * kStep, 1.0f});
                op.n = m_rng.pick(std::vector<int>{0, -1, -1000, 1, 1, 10, 1000000000});
                op.b = m_rng.pick(std::vector<float>{kStep, kStep, 0.0f, kNan, -kStep, 1e-30f, 1e-9f, kInf});
                op.choice = "step-args";
            }
            // The mirror follows stock's time; a world may instead turn an ambiguous call away and
            // keep a larger local time, which a microsecond fixed step with 10^9 substeps allowed
            // would turn into millions of substeps (a hang, seed 10349): never that pair.
            if (op.n > kMaxSubstepsPerCall && op.b > 0.0f && op.b < 1e-3f && attempt <= 20) continue;
            float t = *localTime;
            int simulated = 0;
            ArgClass cls = classify(op.a, op.n, op.b, t);
            if (cls != ArgClass::Bad) {
                bulletSubsteps(op.a, op.n, op.b, &t, &simulated);
                if (simulated > kMaxSubstepsPerCall) continue;  // legitimately slow: not this one
            }
            // Stock Bullet would run a bad call for ever or write Inf: it never gets one (and
            // btgpu must leave the time as it was, so the mirror skips it too).
            op.stockSafe = cls != ArgClass::Bad;
            if (m_skip.has(op.choice)) {
                op = Op();
                op.a = op.b = kStep;
                t = *localTime;
                bulletSubsteps(op.a, op.n, op.b, &t, &simulated);
            }
            *localTime = t;
            m_r.ops.push_back(op);
            return;
        }
    }

    void makeTimeline()
    {
        const Profile p = m_r.profile;
        std::vector<int> badTargets = bodiesIn(Role::Bad, false);
        std::vector<int> extremeTargets = bodiesIn(Role::Extreme, false);
        std::vector<int> normal = bodiesIn(Role::Normal, false);
        std::vector<bool> inWorld(m_r.bodies.size());
        for (size_t i = 0; i < m_r.bodies.size(); ++i) inWorld[i] = m_r.bodies[i].atStart;
        const int steps = m_rng.between(3, 9);
        float localTime = 0.0f;
        bool gravityBad = false;
        for (int s = 0; s < steps; ++s) {
            int changes = s == 0 ? 0 : m_rng.between(0, 3);
            for (int k = 0; k < changes; ++k) {
                int what = m_rng.below(10);
                if (what < 4 && !badTargets.empty() && p != Profile::Extreme)
                    badOp(m_rng.pick(badTargets));
                else if (what < 4 && !extremeTargets.empty())
                    extremeOp(m_rng.pick(extremeTargets));
                else if (what < 6 && !normal.empty())
                    goodOp(m_rng.pick(normal));
                else if (what < 8) {
                    // Remove a body that is in, or add one that is out (never the probe).
                    int body = m_rng.below(int(m_r.bodies.size()));
                    if (body == m_r.probe) continue;
                    Op op = bodyOp(inWorld[size_t(body)] ? OpKind::Remove : OpKind::Add, body,
                                   inWorld[size_t(body)] ? "remove" : "add");
                    inWorld[size_t(body)] = !inWorld[size_t(body)];
                    push(op);
                } else if (what == 8 && (p == Profile::BadBodies || p == Profile::CpuPath) && m_rng.chance(0.3)) {
                    Op op;
                    op.kind = OpKind::WorldGravity;
                    op.v = gravityBad ? btVector3(0, -10, 0) : badVec(m_rng, 10);
                    op.choice = gravityBad ? "world-gravity" : "bad-world-gravity";
                    gravityBad = !gravityBad;
                    push(op);
                } else if (what == 8) {
                    Op op;
                    op.kind = OpKind::WorldGravity;
                    op.v = btVector3(m_rng.range(-2, 2), m_rng.range(-20, -5), m_rng.range(-2, 2));
                    op.choice = "world-gravity";
                    push(op);
                }
            }
            // Bodies built out of the world join at their first chance.
            for (size_t i = 0; i < m_r.bodies.size(); ++i)
                if (!m_r.bodies[i].atStart && !inWorld[i] && s == 1) {
                    push(bodyOp(OpKind::Add, int(i), "add"));
                    inWorld[i] = true;
                }
            stepOp(&localTime, p == Profile::StepArguments && m_rng.chance(0.6));
        }
    }

    Rng m_rng;
    const Skip& m_skip;
    Recipe m_r;
};

}  // namespace

const char* toString(ArgClass c)
{
    return c == ArgClass::Normal ? "normal" : c == ArgClass::Bad ? "bad" : "ambiguous";
}

bool Skip::has(const std::string& choice) const
{
    for (const std::string& n : names)
        if (!n.empty() && (choice == n || choice.rfind(n + "+", 0) == 0)) return true;
    return false;
}

ArgClass classify(float dt, int maxSubSteps, float fixedStep, float localTime)
{
    if (!std::isfinite(dt)) return ArgClass::Bad;
    if (maxSubSteps == 0) {
        if (std::fabs(dt) >= 1e6f) return ArgClass::Bad;  // one variable step that long overflows
        if (dt < 0 || !std::isfinite(fixedStep) || fixedStep <= 0) return ArgClass::Ambiguous;
        return ArgClass::Normal;
    }
    if (!std::isfinite(fixedStep) || fixedStep <= 0) return ArgClass::Bad;
    if (double(localTime + dt) / double(fixedStep) >= double(INT_MAX)) return ArgClass::Bad;
    if (dt < 0 || maxSubSteps < 0) return ArgClass::Ambiguous;
    return ArgClass::Normal;
}

int bulletSubsteps(float dt, int maxSubSteps, float fixedStep, float* localTime, int* simulated)
{
    // btDiscreteDynamicsWorld::stepSimulation's bookkeeping, in the same float operations.
    int n = 0;
    if (maxSubSteps) {
        *localTime += dt;
        if (*localTime >= fixedStep) {
            n = int(*localTime / fixedStep);
            *localTime -= float(n) * fixedStep;
        }
    } else {
        *localTime = 0.0f;  // m_latencyMotionStateInterpolation is on by default
        n = std::fabs(dt) < FLT_EPSILON ? 0 : 1;
        maxSubSteps = n;
    }
    *simulated = n > maxSubSteps ? maxSubSteps : n;
    if (*simulated < 0) *simulated = 0;
    return n;
}

Recipe makeRecipe(std::uint64_t seed, Profile profile, const Skip& skip) { return Generator(seed, profile, skip).make(); }

}  // namespace btgpu::fuzz
