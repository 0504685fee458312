// imported_world.cpp — builds the world (Bullet's default configuration, dispatcher, Dbvt
// broadphase and sequential-impulse solver, as Bullet's examples use), runs the importer on a
// checked file, then restores each body from its record and re-adds every body in the file's
// order with the file's collision filter group and mask (the importer adds them with the
// defaults, and pairs found then would survive a later filter change).
#include "compare/imported_world.h"

#include <BulletFileLoader/btBulletFile.h>
#include <BulletWorldImporter/btBulletWorldImporter.h>

#include "btgpu/btGpuDynamicsWorld.h"
#include "compare/restore_bodies.h"

namespace btgpu::compare {
namespace {

// The importer's map from a file record to the object it made is protected; this exposes it.
class RecordingImporter : public btBulletWorldImporter {
public:
    using btBulletWorldImporter::btBulletWorldImporter;
    btRigidBody* bodyFor(const void* record)
    {
        btCollisionObject** found = m_bodyMap.find(btHashPtr(record));
        return found ? btRigidBody::upcast(*found) : nullptr;
    }
};

}  // namespace

ImportedWorld::~ImportedWorld()
{
    if (m_importer) m_importer->deleteAllData();  // removes and deletes constraints, bodies, shapes
    m_importer.reset();
    m_world.reset();
}

int ImportedWorld::constraints() const { return m_world->getNumConstraints(); }

int ImportedWorld::contacts() const
{
    if (m_gpu && m_gpu->isGpuPath()) return m_gpu->report().contacts;
    int n = 0;
    btDispatcher* d = m_world->getDispatcher();
    for (int i = 0; i < d->getNumManifolds(); ++i) n += d->getManifoldByIndexInternal(i)->getNumContacts() > 0 ? 1 : 0;
    return n;
}

std::unique_ptr<ImportedWorld> ImportedWorld::load(const FileCheck& file, Engine engine, const Config& config,
                                                   std::string& error)
{
    if (!file.ok) {
        error = file.error;
        return nullptr;
    }
    std::unique_ptr<ImportedWorld> w(new ImportedWorld());
    w->m_configuration = std::make_unique<btDefaultCollisionConfiguration>();
    w->m_dispatcher = std::make_unique<btCollisionDispatcher>(w->m_configuration.get());
    w->m_broadphase = std::make_unique<btDbvtBroadphase>();
    w->m_solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    if (engine == Engine::Gpu) {
        auto* gpu = new btGpuDynamicsWorld(w->m_dispatcher.get(), w->m_broadphase.get(), w->m_solver.get(),
                                           w->m_configuration.get(), config);
        w->m_gpu = gpu;
        w->m_world.reset(gpu);
    } else {
        w->m_world = std::make_unique<btDiscreteDynamicsWorld>(w->m_dispatcher.get(), w->m_broadphase.get(),
                                                               w->m_solver.get(), w->m_configuration.get());
    }

    w->m_buffer = file.bytes;
    const size_t size = w->m_buffer.size();
    w->m_buffer.resize(size + 16, 0);
    auto importer = std::make_unique<RecordingImporter>(w->m_world.get());
    importer->setVerboseMode(0);
    std::unique_ptr<bParse::btBulletFile> bullet(new bParse::btBulletFile(w->m_buffer.data(), int(size)));
    const bool loaded = importer->loadFileFromMemory(bullet.get());
    RecordingImporter* rec = importer.get();
    w->m_importer = std::move(importer);
    if (!loaded) {
        error = "Bullet's importer rejected the file (its DNA or header did not parse)";
        return nullptr;
    }
    const bool dbl = (bullet->getFlags() & bParse::FD_DOUBLE_PRECISION) != 0;
    Restoration& r = w->m_restoration;

    for (int i = 0; i < bullet->m_dynamicsWorldInfo.size(); ++i) {
        w->m_fileTimeStep = dbl ? double(((btDynamicsWorldDoubleData*)bullet->m_dynamicsWorldInfo[i])->m_solverInfo.m_timeStep)
                                : double(((btDynamicsWorldFloatData*)bullet->m_dynamicsWorldInfo[i])->m_solverInfo.m_timeStep);
    }

    // Bodies in file order, each with its record, restored before re-adding.
    struct Entry {
        btRigidBody* body;
        const void* record;
        bool rigid;
    };
    std::vector<Entry> entries;
    int missing = 0;
    auto take = [&](const void* record, bool rigid, const char* name) {
        btRigidBody* b = rec->bodyFor(record);
        if (!b) {
            ++missing;
            return;
        }
        entries.push_back({b, record, rigid});
        w->m_bodies.push_back(b);
        w->m_names.push_back(name ? name : "");
    };
    for (int i = 0; i < bullet->m_rigidBodies.size(); ++i) {
        const void* rb = bullet->m_rigidBodies[i];
        take(rb, true,
             dbl ? ((const btRigidBodyDoubleData*)rb)->m_collisionObjectData.m_name : ((const btRigidBodyFloatData*)rb)->m_collisionObjectData.m_name);
    }
    for (int i = 0; i < bullet->m_collisionObjects.size(); ++i) {
        const void* co = bullet->m_collisionObjects[i];
        take(co, false, dbl ? ((const btCollisionObjectDoubleData*)co)->m_name : ((const btCollisionObjectFloatData*)co)->m_name);
    }
    for (Entry& e : entries) {
        if (e.rigid && dbl) restoreRigidBody(*e.body, *(const btRigidBodyDoubleData*)e.record, r);
        else if (e.rigid) restoreRigidBody(*e.body, *(const btRigidBodyFloatData*)e.record, r);
        else if (dbl) restoreCollisionObject(*e.body, *(const btCollisionObjectDoubleData*)e.record, r);
        else restoreCollisionObject(*e.body, *(const btCollisionObjectFloatData*)e.record, r);
    }
    for (Entry& e : entries) w->m_world->removeRigidBody(e.body);
    int refiltered = 0;
    for (Entry& e : entries) {
        const auto filter = [&](const auto& c) {
            if (c.m_uniqueId == -1) {
                w->m_world->addRigidBody(e.body);  // it had no broadphase handle when saved
                return;
            }
            const short defaultGroup = e.body->isStaticOrKinematicObject() ? short(btBroadphaseProxy::StaticFilter)
                                                                           : short(btBroadphaseProxy::DefaultFilter);
            const short defaultMask = e.body->isStaticOrKinematicObject()
                                          ? short(btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter)
                                          : short(btBroadphaseProxy::AllFilter);
            if (c.m_collisionFilterGroup != defaultGroup || c.m_collisionFilterMask != defaultMask) ++refiltered;
            w->m_world->addRigidBody(e.body, c.m_collisionFilterGroup, c.m_collisionFilterMask);
        };
        if (e.rigid && dbl) filter(((const btRigidBodyDoubleData*)e.record)->m_collisionObjectData);
        else if (e.rigid) filter(((const btRigidBodyFloatData*)e.record)->m_collisionObjectData);
        else if (dbl) filter(*(const btCollisionObjectDoubleData*)e.record);
        else filter(*(const btCollisionObjectFloatData*)e.record);
    }
    if (refiltered) r.restored["collision filter group and mask"] = refiltered;
    for (Entry& e : entries) {
        if (e.rigid && dbl) restoreAfterAdd(*e.body, *(const btRigidBodyDoubleData*)e.record, r);
        else if (e.rigid) restoreAfterAdd(*e.body, *(const btRigidBodyFloatData*)e.record, r);
        else if (dbl) restoreAfterAdd(*e.body, *(const btCollisionObjectDoubleData*)e.record, r);
        else restoreAfterAdd(*e.body, *(const btCollisionObjectFloatData*)e.record, r);
    }

    if (missing) r.notes.push_back(std::to_string(missing) + " bodies whose shape the importer could not build were left out");
    if (bullet->m_softBodies.size()) r.notes.push_back(std::to_string(bullet->m_softBodies.size()) + " soft bodies in the file are not imported");
    if (bullet->m_multiBodies.size()) r.notes.push_back(std::to_string(bullet->m_multiBodies.size()) + " multibodies in the file are not imported");
    if (bullet->m_contactManifolds.size())
        r.notes.push_back(std::to_string(bullet->m_contactManifolds.size()) +
                          " saved contact manifolds are not imported: both worlds start with cold contacts");
    const int constraintRecords = bullet->m_constraints.size();
    if (constraintRecords != w->m_world->getNumConstraints())
        r.notes.push_back(std::to_string(constraintRecords - w->m_world->getNumConstraints()) +
                          " constraints in the file were not imported (a kind or body the importer does not know)");
    return w;
}

}  // namespace btgpu::compare

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <thread>

namespace btgpu::compare {

constexpr int kProbeSeconds = 120;

std::string probeImport(const FileCheck& file)
{
    std::fflush(nullptr);
    const pid_t child = ::fork();
    if (child < 0) return "";  // no probe possible; the import itself runs next
    if (child == 0) {
        std::string error;
        std::unique_ptr<ImportedWorld> w = ImportedWorld::load(file, Engine::Stock, Config::bulletMode(), error);
        ::_exit(w ? 0 : 3);
    }
    // A damaged count can also make the importer loop for hours (a hull's points are added one by
    // one, each recomputing its bounds): the child gets a deadline.
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kProbeSeconds);
    for (;;) {
        const pid_t done = ::waitpid(child, &status, WNOHANG);
        if (done == child) break;
        if (done < 0 && errno != EINTR) return "";
        if (std::chrono::steady_clock::now() > deadline) {
            ::kill(child, SIGKILL);
            while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
            }
            return "corrupt: Bullet's importer did not finish within " + std::to_string(kProbeSeconds) + " s";
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    if (WIFSIGNALED(status))
        return std::string("corrupt: Bullet's importer crashed on it (") + strsignal(WTERMSIG(status)) + ")";
    if (WIFEXITED(status) && WEXITSTATUS(status) == 3) return "Bullet's importer rejected the file";
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return "corrupt: Bullet's importer failed on it (exit " + std::to_string(WEXITSTATUS(status)) + ")";
    return "";
}

}  // namespace btgpu::compare
