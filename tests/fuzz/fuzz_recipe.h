// fuzz_recipe.h — a fuzz scene as data: the shapes, bodies in far-apart clusters and the
// timeline of app actions (bad values, adds/removes, odd stepSimulation arguments) that one
// seed generates. Plain data, so the same recipe builds on stock Bullet and on btgpu, prints
// as one line, and an op stock cannot survive can be left out of the stock run.
#pragma once
#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

#include <cstdint>
#include <string>
#include <vector>

namespace btgpu::fuzz {

// Which kinds of trouble a scene gets (one GoogleTest case each, so --gtest_filter picks one).
enum class Profile { BadBodies, CpuPath, StepArguments, Extreme, BadShapes };
const char* toString(Profile p);

// Generator choices that can be switched off by name (BTGPU_FUZZ_SKIP=a,b), to get past a known
// crash and see what else fails. Each op and shape carries the choice that made it.
struct Skip {
    std::vector<std::string> names;
    bool has(const std::string& choice) const;
};

enum class ShapeKind { Box, Sphere, Hull, Plane, Capsule, Cylinder, Cone, Compound };

struct ShapeSpec {
    ShapeKind kind = ShapeKind::Box;
    btVector3 size{1, 1, 1};          // box half extents; sphere radius in x; capsule/cone radius x, height y
    std::vector<btVector3> points;    // hull points (maybe duplicate, coplanar, few, non-finite)
    btVector3 normal{0, 1, 0};        // plane
    float constant = 0.0f;            // plane
    std::string choice;               // the generator choice that made it ("box", "hull-coplanar", ...)
};

enum class Motion { Dynamic, Static, Kinematic };

// What a cluster is for. Normal: finite input, usual sizes (asserted finite always). Extreme:
// finite but extreme sizes, masses, speeds or degenerate hulls (asserted finite where stock
// keeps them finite; may be named, as stock disables a body whose AABB overflows). Bad: gets
// bad values (none of its bodies is asserted finite). Probe: one free-falling sphere that
// must keep falling whatever the rest of the scene does.
enum class Role { Normal, Extreme, Bad, Probe };
const char* toString(Role r);

struct ClusterSpec {
    Role role = Role::Normal;
    std::string layout;  // "pile" (all in one spot), "stack", "scatter", "single"
    btVector3 centre{0, 0, 0};
    float radius = 1.0f;
    bool ground = false;  // has its own static ground box (else the world's plane, if any)
};

struct BodySpec {
    int cluster = 0;
    int shape = 0;  // index into Recipe::shapes; a shape is shared only by bodies of one cluster
    Motion motion = Motion::Dynamic;
    float mass = 1.0f;
    btTransform start = btTransform::getIdentity();
    btVector3 linVel{0, 0, 0}, angVel{0, 0, 0};
    float friction = 0.5f, restitution = 0.0f;
    bool atStart = true;      // added before the first step (else by an Add op)
    bool ownGravity = false;  // BT_DISABLE_WORLD_GRAVITY with gravity (0, -10, 0): the probe
    std::string choice;       // "" or the choice that made the body itself odd
    bool stockSafe = true;    // stock Bullet survives the body (else left out of the stock run)
};

enum class OpKind {
    Step,           // stepSimulation(a, n, b)
    LinVel, AngVel, Teleport, Force, Torque, BodyGravity, Damping, Friction, Restitution,
    LinFactor, AngFactor, Sleeping, MassProps, Scaling, Margin, MoveKinematic,
    WorldGravity, Remove, Add
};
const char* toString(OpKind k);

struct Op {
    OpKind kind = OpKind::Step;
    int body = -1;             // target body (shape ops: the target's shape)
    btVector3 v{0, 0, 0};      // vector value; Teleport: origin; MassProps: inertia
    btVector3 w{0, 0, 0};      // Teleport: basis row 0 scale (NaN there makes the basis bad)
    float a = 0.0f, b = 0.0f;  // Step: dt, fixed step; Damping/Sleeping: lin, ang; MassProps: mass
    int n = 1;                 // Step: maxSubSteps
    std::string choice;        // generator choice (for BTGPU_FUZZ_SKIP and the recipe line)
    bool stockSafe = true;     // stock Bullet survives it (else left out of the stock run)
};

struct Recipe {
    std::uint64_t seed = 0;
    Profile profile = Profile::BadBodies;
    bool groundPlane = false;  // a static plane under every cluster (never given bad values)
    btVector3 planeNormal{0, 1, 0};
    std::vector<ShapeSpec> shapes;
    std::vector<ClusterSpec> clusters;
    std::vector<BodySpec> bodies;
    std::vector<Op> ops;
    // btgpu's Config (public): device substeps, solver kind, profiling, AABB sync.
    int internalSubsteps = 1;
    bool jacobi = false;
    bool soft = false;  // Config::solver = Auto (the default: the soft step) instead of BatchedPgs
    bool profiling = false;
    bool syncAabbs = true;
    int probe = -1;      // body index of the free-falling probe
    float farX = 0.0f;   // x beyond every cluster (where the end-of-scene probe goes)
};

Recipe makeRecipe(std::uint64_t seed, Profile profile, const Skip& skip);
// One line: clusters, bodies by choice, and the op timeline ("s2" = before the 2nd step).
std::string describe(const Recipe& r);

// Bullet's stepSimulation arguments, sorted. Normal: stock's time bookkeeping applies and the
// returned substeps must equal stock's. Bad (non-finite dt or fixed step, fixed step <= 0,
// substep count past int): simulate nothing, leave every body as it was, return 0, name the
// argument in report().issues. Ambiguous (negative dt or maxSubSteps, fixed step ignored with
// maxSubSteps 0): either Bullet's meaning or reported as bad; never NaN or a crash.
enum class ArgClass { Normal, Ambiguous, Bad };
const char* toString(ArgClass c);
ArgClass classify(float dt, int maxSubSteps, float fixedStep, float localTime);
// Stock's time bookkeeping for one call (localTime updated); returns the substeps it reports
// and sets *simulated to the substeps it actually runs (clamped to maxSubSteps).
int bulletSubsteps(float dt, int maxSubSteps, float fixedStep, float* localTime, int* simulated);

}  // namespace btgpu::fuzz
