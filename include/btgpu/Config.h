// Config.h — every option of a btGpuDynamicsWorld: device choice, what to keep in step with
// the CPU side, contact and solver settings the btContactSolverInfo does not carry.
// No global variable changes behaviour: everything lives here (BTGPU_DEVICE, the one
// environment override, picks the device).
#pragma once
#include <cstddef>
#include <functional>
#include <string>

namespace btgpu {

struct Issue;

// How the contacts are solved. BatchedPgs: projected Gauss-Seidel as btSequentialImpulse-
// ConstraintSolver, batched by graph coloring (contacts of one color in parallel).
// JacobiMassSplitting: every contact in parallel against copies of its bodies holding 1/n of
// their mass, averaged after each iteration (Tonge et al. 2012): no coloring, two launches per
// iteration whatever the scene, but slower to converge per iteration.
// SoftStep: Box2D v3's soft step on the same colored graph: the step cut into substeps (each
// integrate velocities, warm start, one soft solve, integrate positions, one relax), contacts as
// damped springs of SoftStepConfig::contactHertz whose separation follows the bodies through the
// substeps (the narrowphase still runs once a step), restitution after the substeps; joints as
// their Bullet rows, solved each substep. Stiff scenes (mass ratios, tall stacks, pyramids)
// stand where the batched PGS drifts; it is not stock's trajectory (see README, solver modes).
// Auto (the default): the soft step, or the batched PGS while the world uses a Bullet feature only
// the batched PGS serves (friction anchors, m_sor, a negative m_globalCfm), where SoftStep would
// send the world to the CPU path. BatchedPgs (Config::bulletMode()) is the mode whose answers
// follow stock's solver: pick it where the app's behaviour must match stock Bullet's (regression
// runs against stock, tuned games); the default is the one that holds stiff scenes up.
// Report::solver says which ran, Report::solverReason why not the soft step. A switch between
// them (the app starts or stops using such a feature) starts the contacts afresh, as a
// rebuild does: one step without warm start.
enum class SolverKind { BatchedPgs, JacobiMassSplitting, SoftStep, Auto };

// The soft step's settings (SolverKind::SoftStep only).
struct SoftStepConfig {
    // Substeps a fixed step is cut into; 0: btContactSolverInfo::m_numIterations of them (10 by
    // default; more for mass ratios, below). A substep sweeps the colored graph twice (solve,
    // relax) and the bodies twice (forces' share with the warm start, positions), a batched-PGS
    // iteration the graph twice plus a push sweep; the soft rows are heavier (two friction rows
    // a point, separations followed through the substeps): about 1.6-2x the PGS's solve.
    int substeps = 0;
    // With substeps 0, more substeps where the step needs them: Gauss-Seidel hands a heavy body
    // resting on a light one only the light one's share of each correction, so a stack of mass
    // ratio r needs about 1.3 sqrt(r) substeps to stand (1-D model, 3-D runs: 100:1 stands at
    // 10, a 400 kg plank on 1 kg boxes at 20-26, 1,000:1 at 40), and a heavy box landing off
    // the light one's centre about twice that (1,000:1, 30-45 cm off: at 42 the pair rocks and
    // walks, at 64 it settles). Each step takes the least n >= m_numIterations with n^2 >=
    // (this)^2 r, up to maxSubsteps, where r is the largest mass ratio (heavier over lighter) of
    // a contact or joint between two dynamic bodies in this step (Report::softSubsteps says what
    // the last step took; a ratio that needs more than maxSubsteps is reported once, an
    // Issue::Kind::Difference). 0: always m_numIterations; so it is with heldMassRatio on (the
    // other cure: held at 64 substeps, a 1,000:1 pair sinks metres).
    float substepsPerRootMassRatio = 2.0f;
    int maxSubsteps = 128;
    // Hz: the contacts' spring (capped at an eighth of the substep rate; twice this against a
    // static or kinematic body) and its damping ratio. Box2D's are 30 Hz and 10; 60 Hz holds
    // the exact towers of 20 and 30 unit boxes that 30 Hz lets rock (README, solver modes).
    float contactHertz = 60.0f;
    float dampingRatio = 10.0f;
    // m/s: the fastest the spring pushes a penetration apart (Box2D's contactSpeed). 0: the
    // fastest stock pushes one with real velocity, m_erp x |m_splitImpulsePenetrationThreshold| /
    // the fixed step (0.48 m/s at Bullet's defaults; deeper, its split impulse moves the bodies
    // without velocity), or Box2D's 3 m/s with m_splitImpulse off. Box2D's 3 m/s for every
    // penetration made bodies spawned overlapping (a stack of convex-hull crates, whose margins
    // overlap by 8 cm) fly apart: the relax does not take all of that velocity back.
    float pushSpeed = 0.0f;
    // Friction rows in the biased solve as well as the relax (as Box2D's current sources do).
    // Off by default: with them in both, the tower of 30 rocks. Friction against fixed bodies is
    // warm-started across steps either way (a box resting on a slope creeps without it).
    bool frictionInSolve = false;
    // m: the most a loaded contact spring sinks. Box2D's spring is relative to the contact
    // point's effective mass, so it sinks by its load / (effective mass x omega^2): a 1,000 kg
    // box on a 1 kg one 28 cm at 30 Hz, the bottom of a tower of 30 unit boxes 2 cm. A contact
    // whose last step's most loaded point would sink further is stiffened for this step, all its
    // points alike (stiffness r times, damping r^1.5 times) until that point would not. 0:
    // Box2D's springs. 0.7 mm: the towers of 20 and 30 settle within 13 and 27 mm and no box
    // of the pyramid of 50 moves more than 38 mm (README, solver modes; 1 mm stiffened point by
    // point until 2026-12-05 left the towers rocking; one factor at 1 mm, the pyramid 56 mm).
    // A thin body's contacts sink at most 1% of its depth along the normal (and at least 0.01 mm
    // is allowed): three 1 cm boxes stacked rest 0.05 mm deep, not 0.28 mm.
    float maxSag = 0.0007f;
    // Opt-in (0: off, the default): a light body under a much heavier one (masses differing by
    // more than this). Gauss-Seidel hands the heavy body only the light one's share of each
    // correction, so the load builds over many substeps and the pair, stiffened to maxSag,
    // rings until it falls (a 1,000 kg box on a 1 kg one at 10 substeps; a 400 kg plank on two
    // 1 kg boxes rocks). Where the light body rests on one fixed body, their contact's normal
    // rows hold it (the heavy body takes each correction whole) and pass its reaction straight
    // to that support's points, balancing force and torque on it: with 100 both stand still at
    // 10 substeps. Not the default: a heavy body dropped near the light one's edge tips off
    // and the light one is thrown (tens of m/s; README, solver modes).
    float heldMassRatio = 0.0f;
};

struct Config {
    // "" (first GPU, else a CPU device), "gpu", "cpu", or a substring of the platform or device
    // name. The environment variable BTGPU_DEVICE overrides it.
    std::string device;
    // Run on the base class's CPU path regardless (for comparisons and debugging).
    bool forceCpu = false;
    // Keep the CPU broadphase's AABBs current after each step so rayTest, convexSweepTest and
    // contactTest see the bodies where they are. Apps that never query may turn it off.
    bool syncBroadphaseAabbs = true;
    // Keep the app's dispatcher holding the contact manifolds stock Bullet would
    // (getNumManifolds, getManifoldByIndexInternal: points, impulses, lifetimes) after each
    // step. Apps that never read contacts may turn it off: the dispatcher then holds none.
    bool fillDispatcherManifolds = true;
    // With the fill on: also hold stock's empty manifolds, one for every broadphase pair its
    // dispatcher has collided (its algorithm's, made at the pair's first collision and given back
    // when the pair leaves the pair cache; per compound child whose AABB overlaps), so that
    // getNumManifolds() is stock's count. By default (deviceEmptyManifolds) the pairs are stock's
    // Dbvt leaves' overlaps found on the device (stage broadphase_leaves), stock's lazy removal of
    // pairs emulated on the host; stockEmptyManifolds instead runs Bullet's own broadphase on the
    // host at each internal step (exact, at stock's cost for it: about 1 ms at 1,000 boxes on one
    // core, hundreds at 30,000). With both off the dispatcher holds the manifolds with points only.
    bool deviceEmptyManifolds = true;
    // ... in a world of up to this many collision objects: holding every empty manifold costs the
    // host (H200 host, 200 frames of falling cubes: +0.2 ms a frame at 1,000, +24 ms at 32,768,
    // +151 ms at 112,500), so a bigger world holds the manifolds with points only unless raised.
    int deviceEmptyManifoldsUpTo = 8192;
    bool stockEmptyManifolds = false;
    // Ghost objects' overlaps on the GPU path come from Bullet's own broadphase, updated on the
    // host at each internal step. In a world of up to this many collision objects it is stock's
    // whole pair update (the ghosts' lists exactly stock's, step by step); in a bigger one only the
    // ghosts' pairs are updated, from Bullet's own tree and leaves (the pairs stock adds, added at
    // stock's step; one that stops overlapping goes at once, where stock's lazy cleanup takes up to
    // ~10 steps), so a character or trigger in a big world does not cost stock's broadphase.
    int ghostPairsExactUpTo = 4096;
    // ... and in a bigger world whose ghosts are all triggers (no contact response; a
    // character's ghost, moved inside the step by its action's setAabb, keeps the tree) the
    // ghosts' pairs come from the device: the Dbvt leaves stage
    // broadphase_leaves keeps as stock's setAabb does, stock's pair cache followed on the host
    // with its lazy cleanup (pairs join at stock's step; the cache's order is not stock's, so a
    // pair may leave a few steps apart from stock's), the ghost pairs added to and removed from
    // Bullet's pair cache (its ghost callback, an app's ghost subclass, as stock's). No broadphase
    // work on the host: a ghost costs the leaf stage and the read-back of its changes. Off: the
    // ghosts' pairs from Bullet's own tree on the host, as above.
    bool ghostPairsFromDevice = true;
    // Per-stage device times from OpenCL profiling events (Report::stageMs), taken on one
    // stepSimulation call in profileEvery (events cost host time on every launch).
    bool profile = false;
    int profileEvery = 1;
    // m: points closer than this become contacts (Bullet's gContactBreakingThreshold). Left at
    // 0.02, the world follows gContactBreakingThreshold when the app changes it.
    float contactThreshold = 0.02f;
    // The contact solver (SolverKind above): Auto, the soft step, by default since 2026-12-06;
    // bulletMode() below for the batched PGS whose answers follow stock Bullet's.
    SolverKind solver = SolverKind::Auto;
    SoftStepConfig softStep;
    // Device substeps per fixed step (stepSimulation's own substeps are not touched: the app
    // sees the same steps, motion states and interpolation). Stiff scenes (mass ratios, tall
    // stacks) converge much better from more, shorter steps than from more iterations; each
    // costs a full pipeline pass on the device and nothing on the host.
    int internalSubsteps = 1;
    // Upper bound on the solver's batches (graph colors) per iteration; contacts the coloring
    // cannot place within it run serially. The number actually launched follows the scene
    // (BatchedPgs only).
    int maxColors = 64;
    // A body whose bounding size exceeds this multiple of the median body size is paired by
    // brute force against all bodies instead of through the uniform grid.
    float largeBodyFactor = 4.0f;
    // Device memory this world may hold in buffers, bytes (0: as much as the device gives).
    // Running out, at this limit or the device's own, is an OpenCL failure: reported, and the
    // world continues on the CPU path from where it was.
    std::size_t deviceMemoryLimit = 0;
    // Called for each problem the world reports (bad body input, OpenCL failure, fallback).
    std::function<void(const Issue&)> onIssue;

    // The defaults with the bullet mode's solver (SolverKind::BatchedPgs): Bullet's
    // sequential-impulse rows, order, friction and split impulse, batched; the mode to compare
    // against stock Bullet with.
    static Config bulletMode()
    {
        Config c;
        c.solver = SolverKind::BatchedPgs;
        return c;
    }
};

}  // namespace btgpu
