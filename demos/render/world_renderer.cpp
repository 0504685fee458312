// world_renderer.cpp — fixed-function lighting, one cached triangle mesh per shape.
#include "render/world_renderer.h"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>

namespace btgpu::render {

namespace {

void drawMesh(const Mesh& m, const btTransform& t, const btVector3& colour)
{
    if (m.positions.empty()) return;
    btScalar matrix[16];
    t.getOpenGLMatrix(matrix);
    glPushMatrix();
    glMultMatrixf(matrix);
    glColor3f(colour.x(), colour.y(), colour.z());
    glVertexPointer(3, GL_FLOAT, 0, m.positions.data());
    glNormalPointer(GL_FLOAT, 0, m.normals.data());
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(m.positions.size() / 3));
    glPopMatrix();
}

// A light and a dark grey check in a 2 x 2 texture, mipmapped (far ground fades to their mean
// instead of shimmering), laid on statics in world x and z by texture-coordinate generation.
void checkerOn(unsigned& texture, float checkMetres)
{
    if (!texture) {
        const GLubyte texels[2 * 2 * 3] = {255, 255, 255, 212, 212, 212, 212, 212, 212, 255, 255, 255};
        glGenTextures(1, &texture);
        glBindTexture(GL_TEXTURE_2D, texture);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexParameteri(GL_TEXTURE_2D, GL_GENERATE_MIPMAP, GL_TRUE);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB, 2, 2, 0, GL_RGB, GL_UNSIGNED_BYTE, texels);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    }
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    // Planes given while the modelview holds only the view: they are world x and z.
    const float s[4] = {0.5f / checkMetres, 0, 0, 0}, t[4] = {0, 0, 0.5f / checkMetres, 0};
    glTexGeni(GL_S, GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
    glTexGeni(GL_T, GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
    glTexGenfv(GL_S, GL_EYE_PLANE, s);
    glTexGenfv(GL_T, GL_EYE_PLANE, t);
}

void texturing(bool on)
{
    if (on) glEnable(GL_TEXTURE_2D), glEnable(GL_TEXTURE_GEN_S), glEnable(GL_TEXTURE_GEN_T);
    else glDisable(GL_TEXTURE_2D), glDisable(GL_TEXTURE_GEN_S), glDisable(GL_TEXTURE_GEN_T);
}

}  // namespace

btVector3 objectColour(const btCollisionObject& object, int worldIndex)
{
    if (object.isStaticOrKinematicObject()) return btVector3(0.58f, 0.56f, 0.50f);
    static const btVector3 palette[6] = {{0.90f, 0.35f, 0.20f}, {0.20f, 0.55f, 0.85f}, {0.95f, 0.75f, 0.15f},
                                         {0.30f, 0.70f, 0.35f}, {0.70f, 0.35f, 0.75f}, {0.15f, 0.70f, 0.70f}};
    return palette[worldIndex % 6];
}

const Mesh& WorldRenderer::mesh(const btCollisionShape& shape)
{
    auto it = m_meshes.find(&shape);
    if (it == m_meshes.end()) it = m_meshes.emplace(&shape, meshForShape(shape)).first;
    return it->second;
}

void WorldRenderer::draw(const btCollisionWorld& world, const Camera& camera, const std::vector<ExtraShape>& extras,
                         const std::vector<Line>& lines)
{
    glViewport(0, 0, camera.width, camera.height);
    glClearColor(kBackground[0], kBackground[1], kBackground[2], 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    float m[16];
    glMatrixMode(GL_PROJECTION);
    camera.projectionMatrix(m);
    glLoadMatrixf(m);
    glMatrixMode(GL_MODELVIEW);
    camera.viewMatrix(m);
    glLoadMatrixf(m);

    // A key light from above the camera's left shoulder (set in world space, after the view).
    const btVector3 eye = camera.eye() - camera.target;
    const btVector3 side = eye.cross(btVector3(0, 1, 0)).safeNormalize();
    const btVector3 key = (eye.normalized() + btVector3(0, 1.2f, 0) + side * 0.5f).normalized();
    const float position[4] = {key.x(), key.y(), key.z(), 0};
    const float diffuse[4] = {0.75f, 0.75f, 0.72f, 1}, ambient[4] = {0.32f, 0.33f, 0.36f, 1};
    glEnable(GL_LIGHTING);
    glEnable(GL_LIGHT0);
    glLightfv(GL_LIGHT0, GL_POSITION, position);
    glLightfv(GL_LIGHT0, GL_DIFFUSE, diffuse);
    glLightfv(GL_LIGHT0, GL_AMBIENT, ambient);
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
    glEnable(GL_COLOR_MATERIAL);
    glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
    glShadeModel(GL_SMOOTH);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_NORMAL_ARRAY);

    // Checks of a power of two metres, about a twelfth of the viewing distance.
    checkerOn(m_checker, std::max(0.5f, std::exp2(std::round(std::log2(camera.distance / 12)))));
    const btCollisionObjectArray& objects = world.getCollisionObjectArray();
    for (int i = 0; i < objects.size(); ++i) {
        const btCollisionObject& o = *objects[i];
        texturing(o.isStaticObject());
        drawMesh(mesh(*o.getCollisionShape()), o.getWorldTransform(), objectColour(o, i));
    }
    texturing(false);
    for (const ExtraShape& e : extras)
        if (e.shape) drawMesh(mesh(*e.shape), e.transform, e.colour);
    glDisableClientState(GL_NORMAL_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);

    glDisable(GL_LIGHTING);
    glBegin(GL_LINES);
    for (const Line& l : lines) {
        glColor3f(l.colour.x(), l.colour.y(), l.colour.z());
        glVertex3f(l.from.x(), l.from.y(), l.from.z());
        glVertex3f(l.to.x(), l.to.y(), l.to.z());
    }
    glEnd();
    glFinish();
}

}  // namespace btgpu::render
