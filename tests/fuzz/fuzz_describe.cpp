// fuzz_describe.cpp — a recipe as one line (what a failing seed prints, so a reader sees the
// scene without rerunning it) and the names of the generator's enums.
#include "fuzz_recipe.h"

#include <cmath>
#include <sstream>

namespace btgpu::fuzz {

namespace {

constexpr float kStep = 1.0f / 60.0f;

std::string num(float f)
{
    if (std::isnan(f)) return "nan";
    if (std::isinf(f)) return f > 0 ? "inf" : "-inf";
    std::ostringstream os;
    os.precision(3);
    os << f;
    return os.str();
}

std::string vec(const btVector3& v) { return "(" + num(v.x()) + "," + num(v.y()) + "," + num(v.z()) + ")"; }

}  // namespace

const char* toString(Profile p)
{
    switch (p) {
        case Profile::BadBodies: return "BadBodies";
        case Profile::CpuPath: return "CpuPath";
        case Profile::StepArguments: return "StepArguments";
        case Profile::Extreme: return "Extreme";
        case Profile::BadShapes: return "BadShapes";
    }
    return "?";
}

const char* toString(Role r)
{
    switch (r) {
        case Role::Normal: return "normal";
        case Role::Extreme: return "extreme";
        case Role::Bad: return "bad";
        case Role::Probe: return "probe";
    }
    return "?";
}

const char* toString(OpKind k)
{
    static const char* names[] = {"step",        "linvel",   "angvel",   "teleport", "force",     "torque",   "gravity",
                                  "damping",     "friction", "restitution", "linfactor", "angfactor", "sleeping", "massprops",
                                  "scaling",     "margin",   "kinematic", "world-gravity", "remove", "add"};
    return names[int(k)];
}

std::string describe(const Recipe& r)
{
    std::ostringstream os;
    os << toString(r.profile) << " seed " << r.seed << ": " << (r.groundPlane ? "plane" + vec(r.planeNormal) : "no plane");
    if (r.internalSubsteps != 1) os << " internalSubsteps=" << r.internalSubsteps;
    if (r.jacobi) os << " jacobi";
    if (r.soft) os << " soft";
    if (r.profiling) os << " profiling";
    if (!r.syncAabbs) os << " no-aabb-sync";
    for (size_t c = 0; c < r.clusters.size(); ++c) {
        const ClusterSpec& cl = r.clusters[c];
        os << " | C" << c << " " << toString(cl.role) << " " << cl.layout << (cl.ground ? "+ground" : "") << ":";
        for (size_t i = 0; i < r.bodies.size(); ++i) {
            const BodySpec& b = r.bodies[i];
            if (b.cluster != int(c) || b.choice == "ground") continue;
            os << " b" << i << "=" << r.shapes[size_t(b.shape)].choice;
            if (!b.choice.empty() && b.choice != r.shapes[size_t(b.shape)].choice) os << "[" << b.choice << "]";
            if (b.motion == Motion::Static) os << "/static";
            if (b.motion == Motion::Kinematic) os << "/kinematic";
            if (!b.atStart) os << "/late";
        }
    }
    os << " || ops:";
    int step = 1;
    for (const Op& op : r.ops) {
        if (op.kind == OpKind::Step) {
            os << " step" << step++;
            if (op.a != kStep || op.n != 1 || op.b != kStep || op.a != op.a || op.b != op.b)
                os << "(" << num(op.a) << "," << op.n << "," << num(op.b) << ")";
            continue;
        }
        os << " " << (op.choice.empty() ? toString(op.kind) : op.choice.c_str());
        if (op.body >= 0) os << "(b" << op.body << ")";
        switch (op.kind) {
            case OpKind::LinVel: case OpKind::AngVel: case OpKind::Force: case OpKind::Torque: case OpKind::BodyGravity:
            case OpKind::LinFactor: case OpKind::AngFactor: case OpKind::Scaling: case OpKind::WorldGravity:
            case OpKind::MoveKinematic:
                os << "=" << vec(op.v);
                break;
            case OpKind::Teleport: os << "=" << vec(op.v) << (op.a != 1.0f ? " basis " + num(op.a) : ""); break;
            case OpKind::Friction: case OpKind::Restitution: case OpKind::Margin: os << "=" << num(op.a); break;
            case OpKind::Damping: case OpKind::Sleeping: os << "=" << num(op.a) << "," << num(op.b); break;
            case OpKind::MassProps: os << "=" << num(op.a) << (op.n ? "" : " inertia " + vec(op.v)); break;
            default: break;
        }
        if (!op.stockSafe) os << "{not on stock}";
    }
    return os.str();
}

}  // namespace btgpu::fuzz
