// imported_world.h — a `.bullet` file loaded into a stock btDiscreteDynamicsWorld or a
// btGpuDynamicsWorld with Bullet's btBulletWorldImporter, then every body field the importer
// drops put back from the file's own records (restore_bodies.cpp); what neither can restore is
// listed, so a report says exactly how the loaded scene may differ from the app's.
#pragma once
#include <btBulletDynamicsCommon.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "btgpu/Config.h"
#include "compare/bullet_file_check.h"

class btGpuDynamicsWorld;
class btBulletWorldImporter;

namespace btgpu::compare {

enum class Engine { Stock, Gpu };

// What the loading did to the scene: each entry a field (or world setting) and how many bodies
// it concerned.
struct Restoration {
    std::map<std::string, int> restored;  // put back from the file after the importer dropped it
    std::map<std::string, int> lost;      // in the app's world but not restorable (not in the file, or no setter)
    std::vector<std::string> notes;       // world-level facts (counts of what the importer skipped)
};

class ImportedWorld {
public:
    // Loads a checked file (checkBulletFile). On failure returns nullptr and sets `error`.
    static std::unique_ptr<ImportedWorld> load(const FileCheck& file, Engine engine, const Config& config,
                                               std::string& error);
    ~ImportedWorld();
    ImportedWorld(const ImportedWorld&) = delete;
    ImportedWorld& operator=(const ImportedWorld&) = delete;

    btDiscreteDynamicsWorld& world() { return *m_world; }
    btGpuDynamicsWorld* gpuWorld() { return m_gpu; }  // nullptr for Stock
    // Bodies in the file's order (rigid-body records, then plain collision objects as static
    // bodies): index i is the same body in every world loaded from the same file.
    const std::vector<btRigidBody*>& bodies() const { return m_bodies; }
    const std::vector<std::string>& names() const { return m_names; }
    const Restoration& restoration() const { return m_restoration; }
    int constraints() const;
    // The fixed step the app last stepped with (the solver info's m_timeStep), 0 if unknown.
    double fileTimeStep() const { return m_fileTimeStep; }
    // Manifolds with at least one point after the last step (the btgpu world's own count on the
    // GPU path, where the dispatcher's manifolds are not filled).
    int contacts() const;

private:
    ImportedWorld() = default;
    std::unique_ptr<btDefaultCollisionConfiguration> m_configuration;
    std::unique_ptr<btCollisionDispatcher> m_dispatcher;
    std::unique_ptr<btBroadphaseInterface> m_broadphase;
    std::unique_ptr<btSequentialImpulseConstraintSolver> m_solver;
    std::unique_ptr<btDiscreteDynamicsWorld> m_world;
    btGpuDynamicsWorld* m_gpu = nullptr;
    std::unique_ptr<btBulletWorldImporter> m_importer;
    std::vector<char> m_buffer;  // the file, padded: Bullet's loader scans a few bytes past its end
    std::vector<btRigidBody*> m_bodies;
    std::vector<std::string> m_names;
    Restoration m_restoration;
    double m_fileTimeStep = 0.0;
};

}  // namespace btgpu::compare

namespace btgpu::compare {
// Runs the importer on the file in a child process (fork) first: Bullet's loader trusts the
// records' counts and offsets, and a file that passes the structural check can still make it
// read out of bounds. "" when the child imported it cleanly, else what happened to it.
std::string probeImport(const FileCheck& file);
}  // namespace btgpu::compare
