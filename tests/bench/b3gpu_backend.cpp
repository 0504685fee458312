// b3gpu_backend.cpp — our peer: Bullet3's b3GpuRigidBodyPipeline (libBullet3OpenCL_clew) on
// the same OpenCL device rule as btgpu (BTGPU_DEVICE=gpu|cpu|<name substring>, default first
// GPU else CPU). Set up as Bullet3's own GPU demos do (GpuRigidBodyDemo::initPhysics): SAP
// broadphase, b3Config sized from the scene. Bullet3 code lives only here: it is the peer we
// measure, never a source for the library.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <tuple>
#include <vector>

#include "Bullet3Collision/BroadPhaseCollision/b3DynamicBvhBroadphase.h"
#include "Bullet3Collision/NarrowPhaseCollision/b3Config.h"
#include "Bullet3Collision/NarrowPhaseCollision/b3Contact4.h"
#include "Bullet3Common/b3Logging.h"
#include "Bullet3OpenCL/BroadphaseCollision/b3GpuSapBroadphase.h"
#include "Bullet3OpenCL/Initialize/b3OpenCLUtils.h"
#include "Bullet3OpenCL/RigidBody/b3GpuNarrowPhase.h"
#include "Bullet3OpenCL/RigidBody/b3GpuNarrowPhaseInternalData.h"
#include "Bullet3OpenCL/RigidBody/b3GpuRigidBodyPipeline.h"
#include "bench_backend.h"

namespace btgpu::bench {

namespace {

using Clock = std::chrono::steady_clock;

// Bullet3 reports through global hooks; one b3 pipeline runs at a time, so these are the
// bench's only globals. Zones are host times of B3_PROFILE scopes: the pipeline enqueues
// asynchronously and only some zones end in clFinish, so they are approximate.
struct B3Hooks {
    struct Open { const char* name; Clock::time_point start; };
    std::vector<Open> stack;
    std::map<std::string, double> zoneMs;
    std::string lastError;
    int errors = 0;
};
B3Hooks g_hooks;

void enterZone(const char* name) { g_hooks.stack.push_back({name, Clock::now()}); }
void leaveZone()
{
    if (g_hooks.stack.empty()) return;
    B3Hooks::Open o = g_hooks.stack.back();
    g_hooks.stack.pop_back();
    g_hooks.zoneMs[o.name] += std::chrono::duration<double, std::milli>(Clock::now() - o.start).count();
}
// b3Printf/b3Warning go to stderr so stdout stays a clean Markdown table.
void toStderr(const char* msg) { std::fputs(msg, stderr); }
void onError(const char* msg)
{
    std::fputs(msg, stderr);
    ++g_hooks.errors;
    if (std::strncmp(msg, "b3Error[", 8) != 0) g_hooks.lastError = msg;  // the text, not the file:line header
}

// The device rule of Config::device / BTGPU_DEVICE, applied through b3OpenCLUtils (whose
// clew loader finds libOpenCL.so at run time).
cl_context createContext(std::string* why)
{
    const char* env = std::getenv("BTGPU_DEVICE");
    std::string want = env ? env : "";
    cl_int err = 0;
    if (want.empty() || want == "gpu") {
        cl_context c = b3OpenCLUtils::createContextFromType(CL_DEVICE_TYPE_GPU, &err);
        if (c || want == "gpu") {
            if (!c) *why = "no OpenCL GPU device (BTGPU_DEVICE=gpu)";
            return c;
        }
    }
    if (want.empty() || want == "cpu") {
        cl_context c = b3OpenCLUtils::createContextFromType(CL_DEVICE_TYPE_CPU, &err);
        if (!c) *why = "no OpenCL device";
        return c;
    }
    // A substring of a platform or device name: the first platform whose name or one of
    // whose devices' names contains it.
    int platforms = b3OpenCLUtils_getNumPlatforms(&err);
    for (int p = 0; p < platforms; ++p) {
        cl_platform_id pid = b3OpenCLUtils_getPlatform(p, &err);
        b3OpenCLPlatformInfo pinfo;
        b3OpenCLUtils::getPlatformInfo(pid, &pinfo);
        cl_context c = b3OpenCLUtils_createContextFromPlatform(pid, CL_DEVICE_TYPE_ALL, &err, 0, 0, -1, -1);
        if (!c) continue;
        bool match = std::string(pinfo.m_platformName).find(want) != std::string::npos;
        for (int d = 0; !match && d < b3OpenCLUtils::getNumDevices(c); ++d) {
            b3OpenCLDeviceInfo dinfo;
            b3OpenCLUtils::getDeviceInfo(b3OpenCLUtils::getDevice(c, d), &dinfo);
            match = std::string(dinfo.m_deviceName).find(want) != std::string::npos;
        }
        if (match) return c;
        clReleaseContext(c);
    }
    *why = "no OpenCL platform or device matches BTGPU_DEVICE=" + want;
    return nullptr;
}

// Unit-cube corners, scaled by the half extents when registered.
const float kCube[8][4] = {{-1, -1, -1, 0}, {1, -1, -1, 0}, {-1, 1, -1, 0}, {1, 1, -1, 0},
                           {-1, -1, 1, 0},  {1, -1, 1, 0},  {-1, 1, 1, 0},  {1, 1, 1, 0}};

class B3gpuBackend : public Backend {
public:
    ~B3gpuBackend() override
    {
        delete m_pipeline;
        delete m_dbvt;
        delete m_bp;
        delete m_np;
        if (!m_cacheDir.empty()) std::filesystem::remove_all(m_cacheDir);
        if (m_queue) clReleaseCommandQueue(m_queue);
        if (m_ctx) clReleaseContext(m_ctx);
    }
    std::string name() const override { return "b3gpu"; }
    std::string device() const override { return m_device; }
    std::string notes() const override
    {
        char buf[512];
        std::snprintf(buf, sizeof buf,
                      "b3GpuRigidBodyPipeline + b3GpuSapBroadphase; b3Config maxConvexBodies=%d maxConvexShapes=%d "
                      "maxBroadphasePairs=%d maxContactCapacity=%d maxConvexVertices=%d maxConvexIndices=%d "
                      "maxConvexUniqueEdges=%d maxFacesPerShape=%d; 4 solver iterations (hard-coded in "
                      "b3GpuPgsContactSolver), angular damping 0.99/step (integrate kernel); %s inertia; "
                      "cold kernel builds (fresh binary cache dir)",
                      m_config.m_maxConvexBodies, m_config.m_maxConvexShapes, m_config.m_maxBroadphasePairs,
                      m_config.m_maxContactCapacity, m_config.m_maxConvexVertices, m_config.m_maxConvexIndices,
                      m_config.m_maxConvexUniqueEdges, m_config.m_maxFacesPerShape,
                      m_nativeInertia ? "Bullet3's own (AABB-based, inflated)" : "exact box/sphere");
        return buf;
    }

    bool setUp(const Scene& scene, const Options& options, std::string* why) override
    {
        if (!scene.joints.empty()) {
            // Bullet3's pipeline solves joints on the CPU (bullet3#4); its GPU rigid-body demo
            // path has none to measure against.
            *why = "Bullet3's GPU pipeline has no joints on the device";
            return false;
        }
        b3SetCustomPrintfFunc(toStderr);
        b3SetCustomWarningMessageFunc(toStderr);
        b3SetCustomErrorMessageFunc(onError);
        b3SetCustomEnterProfileZoneFunc(enterZone);
        b3SetCustomLeaveProfileZoneFunc(leaveZone);
        for (const BodySpec& b : scene.bodies)
            if (b.shape != ShapeKind::Box && b.shape != ShapeKind::Sphere) {
                *why = "this backend builds boxes and spheres only (the scene has hulls, planes or compounds)";
                return false;
            }
        m_dt = scene.dt;
        m_nativeInertia = options.b3NativeInertia;
        // Bullet3 caches kernel binaries on disk (in ./cache by default); btgpu caches in
        // memory only. A fresh directory per run makes both first frames cold builds.
        std::string tmpl = (std::filesystem::temp_directory_path() / "btgpu_bench_b3XXXXXX").string();
        if (mkdtemp(tmpl.data())) {
            m_cacheDir = tmpl;
            b3OpenCLUtils_setCachePath(m_cacheDir.c_str());
        }

        m_ctx = createContext(why);
        if (!m_ctx) return false;
        m_dev = b3OpenCLUtils::getDevice(m_ctx, 0);
        b3OpenCLDeviceInfo dinfo;
        b3OpenCLUtils::getDeviceInfo(m_dev, &dinfo);
        m_device = dinfo.m_deviceName;
        cl_int err = 0;
        m_queue = clCreateCommandQueue(m_ctx, m_dev, 0, &err);
        if (!m_queue) {
            *why = "clCreateCommandQueue failed (" + std::to_string(err) + ")";
            return false;
        }

        // Shapes: one collidable per distinct size, like the demos' shared cube shape.
        struct ShapeKey {
            int kind;
            float a, b, c;
            bool operator<(const ShapeKey& o) const { return std::tie(kind, a, b, c) < std::tie(o.kind, o.a, o.b, o.c); }
        };
        std::map<ShapeKey, int> shapes;
        int hulls = 0;
        for (const BodySpec& b : scene.bodies) {
            ShapeKey k = b.shape == ShapeKind::Box ? ShapeKey{0, b.half[0], b.half[1], b.half[2]}
                                                   : ShapeKey{1, b.radius, 0, 0};
            if (shapes.emplace(k, -1).second && b.shape == ShapeKind::Box) ++hulls;
        }
        // Limits as GpuRigidBodyDemo sizes them (bodies + slack, 16 pairs per body, contacts
        // = pairs), never below Bullet3's defaults; hull tables from the scene's box count.
        const int bodies = int(scene.bodies.size());
        m_config.m_maxConvexBodies = std::max(m_config.m_maxConvexBodies, bodies + 10);
        m_config.m_maxConvexShapes = std::max(m_config.m_maxConvexShapes, int(shapes.size()) + 10);
        m_config.m_maxBroadphasePairs = 16 * m_config.m_maxConvexBodies;
        m_config.m_maxContactCapacity = m_config.m_maxBroadphasePairs;
        m_config.m_maxConvexVertices = std::max(m_config.m_maxConvexVertices, 8 * hulls + 64);
        m_config.m_maxConvexIndices = std::max(m_config.m_maxConvexIndices, 24 * hulls + 256);
        m_config.m_maxConvexUniqueEdges = std::max(m_config.m_maxConvexUniqueEdges, 3 * hulls + 64);

        m_np = new b3GpuNarrowPhase(m_ctx, m_dev, m_queue, m_config);
        m_bp = new b3GpuSapBroadphase(m_ctx, m_dev, m_queue);
        m_dbvt = new b3DynamicBvhBroadphase(m_config.m_maxConvexBodies);
        m_pipeline = new b3GpuRigidBodyPipeline(m_ctx, m_dev, m_queue, m_np, m_bp, m_dbvt, m_config);
        m_pipeline->setGravity(scene.gravity);

        for (auto& [k, id] : shapes) {
            if (k.kind == 0) {
                float scale[4] = {k.a, k.b, k.c, 1};
                id = m_np->registerConvexHullShape(&kCube[0][0], sizeof(kCube[0]), 8, scale);
            } else {
                id = m_np->registerSphereShape(k.a);
            }
            if (id < 0) {
                *why = "registering a shape failed: " + g_hooks.lastError;
                return false;
            }
        }
        const float identity[4] = {0, 0, 0, 1};
        for (const BodySpec& b : scene.bodies) {
            ShapeKey k = b.shape == ShapeKind::Box ? ShapeKey{0, b.half[0], b.half[1], b.half[2]}
                                                   : ShapeKey{1, b.radius, 0, 0};
            float pos[4] = {b.pos[0], b.pos[1], b.pos[2], 0};
            int index = m_pipeline->registerPhysicsInstance(b.mass, pos, identity, shapes[k], 0, false);
            if (index < 0) {
                *why = "registerPhysicsInstance failed: " + g_hooks.lastError;
                return false;
            }
        }
        setMaterialsAndInertia(scene);
        m_pipeline->writeAllInstancesToGpu();
        m_np->writeAllBodiesToGpu();
        m_bp->writeAabbsToGpu();
        clFinish(m_queue);
        return true;
    }

    FrameTime step() override
    {
        g_hooks.zoneMs.clear();
        auto t0 = Clock::now();
        m_pipeline->stepSimulation(m_dt);
        m_np->readbackAllBodiesToCpu();  // blocking: the frame includes the device work and its readback
        double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        ++m_frame;
        checkOverflow();
        return {ms, -1};
    }

    void poses(std::vector<Pose>& out) override
    {
        const b3RigidBodyData* b = m_np->getBodiesCpu();
        int n = m_np->getNumRigidBodies();
        out.resize(n);
        for (int i = 0; i < n; ++i)
            out[i] = {{b[i].m_pos.x, b[i].m_pos.y, b[i].m_pos.z}, {b[i].m_quat.x, b[i].m_quat.y, b[i].m_quat.z, b[i].m_quat.w}};
    }

    void info(FrameInfo& out, bool detailed) override
    {
        out.stageMs = g_hooks.zoneMs;
        out.pairs = m_bp->getNumOverlap();
        out.manifolds = m_np->getNumContactsGpu();
        out.overflow = m_overflow;
        if (detailed && out.manifolds > 0) {
            const b3Contact4* c = m_np->getContactsCPU();
            long pts = 0;
            for (long i = 0; i < out.manifolds; ++i) pts += c[i].getNPoints();
            out.points = pts;
        }
    }

private:
    // Bullet3 gives every body friction 1, restitution 0, and box inertia from its AABB
    // (2x the extents: 4x the true inertia). Write the scene's values so all backends
    // simulate the same bodies (Options::b3NativeInertia keeps Bullet3's inertia).
    void setMaterialsAndInertia(const Scene& scene)
    {
        b3GpuNarrowPhaseInternalData* d = m_np->getInternalData();
        for (size_t i = 0; i < scene.bodies.size(); ++i) {
            const BodySpec& b = scene.bodies[i];
            b3RigidBodyData& body = d->m_bodyBufferCPU->at(int(i));
            body.m_frictionCoeff = b.friction;
            body.m_restituitionCoeff = b.restitution;
            if (m_nativeInertia || b.mass <= 0) continue;
            float I[3];
            if (b.shape == ShapeKind::Box) {
                float x2 = b.half[0] * b.half[0], y2 = b.half[1] * b.half[1], z2 = b.half[2] * b.half[2];
                I[0] = b.mass / 3 * (y2 + z2), I[1] = b.mass / 3 * (x2 + z2), I[2] = b.mass / 3 * (x2 + y2);
            } else {
                I[0] = I[1] = I[2] = 0.4f * b.mass * b.radius * b.radius;
            }
            b3InertiaData& in = d->m_inertiaBufferCPU->at(int(i));
            in.m_initInvInertia.setValue(1 / I[0], 0, 0, 0, 1 / I[1], 0, 0, 0, 1 / I[2]);
            in.m_invInertiaWorld = in.m_initInvInertia;  // bodies start unrotated
        }
    }

    // Bullet3 clamps at its fixed b3Config limits (with a b3Error) instead of growing: a
    // count at its limit means pairs or contacts were dropped this frame.
    void checkOverflow()
    {
        if (!m_overflow.empty()) return;
        std::string what;
        if (m_bp->getNumOverlap() >= m_config.m_maxBroadphasePairs)
            what = "broadphase pairs hit m_maxBroadphasePairs=" + std::to_string(m_config.m_maxBroadphasePairs);
        else if (m_np->getNumContactsGpu() >= m_config.m_maxContactCapacity)
            what = "contacts hit m_maxContactCapacity=" + std::to_string(m_config.m_maxContactCapacity);
        else if (g_hooks.errors > m_errorsSeen)
            what = "b3Error: " + g_hooks.lastError;
        m_errorsSeen = g_hooks.errors;
        if (!what.empty()) m_overflow = "frame " + std::to_string(m_frame - 1) + ": " + what;
    }

    cl_context m_ctx = nullptr;
    cl_device_id m_dev = nullptr;
    cl_command_queue m_queue = nullptr;
    std::string m_device;
    b3Config m_config;
    b3GpuNarrowPhase* m_np = nullptr;
    b3GpuSapBroadphase* m_bp = nullptr;
    b3DynamicBvhBroadphase* m_dbvt = nullptr;
    b3GpuRigidBodyPipeline* m_pipeline = nullptr;
    float m_dt = 1.0f / 60;
    bool m_nativeInertia = false;
    int m_frame = 0;
    int m_errorsSeen = 0;
    std::string m_overflow;
    std::string m_cacheDir;
};

}  // namespace

std::unique_ptr<Backend> makeB3gpuBackend() { return std::make_unique<B3gpuBackend>(); }

}  // namespace btgpu::bench
