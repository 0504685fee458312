// world_renderer.h — draws a Bullet collision world with the current OpenGL context (fixed
// function, compatibility profile): each object's shape, lit and smooth-shaded, in a colour of
// its own, plus extra shapes (a vehicle's wheels) and lines (rays), seen through a Camera.
#pragma once
#include <map>
#include <vector>

#include "render/camera.h"
#include "render/shape_mesh.h"

namespace btgpu::render {

struct ExtraShape {
    const btCollisionShape* shape = nullptr;
    btTransform transform = btTransform::getIdentity();
    btVector3 colour{0.15f, 0.15f, 0.15f};
};
struct Line {
    btVector3 from, to, colour{1, 0.2f, 0.1f};
};

// The background every pixel without a body keeps (what the render test looks for).
constexpr float kBackground[3] = {0.80f, 0.87f, 0.95f};
// The colour of statics (ground, terrain) and, cycling, of dynamic bodies by world index.
btVector3 objectColour(const btCollisionObject& object, int worldIndex);

// One renderer per OpenGL context (it keeps a texture there).
class WorldRenderer {
public:
    void draw(const btCollisionWorld& world, const Camera& camera, const std::vector<ExtraShape>& extras = {},
              const std::vector<Line>& lines = {});

private:
    const Mesh& mesh(const btCollisionShape& shape);
    std::map<const btCollisionShape*, Mesh> m_meshes;  // shapes do not change while drawn
    unsigned m_checker = 0;  // the ground's texture, in the context this renderer draws with
};

}  // namespace btgpu::render
