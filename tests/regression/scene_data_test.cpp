// scene_data_test.cpp — the plain-data scenes (tests/scenes/scene_specs.h) hold what they say:
// the Voronoi cells tile their cube exactly, each a closed convex cell.
#include <gtest/gtest.h>

#include "scenes/scene_specs.h"

namespace btgpu::test {
namespace {

TEST(SceneData, VoronoiCellsTileTheCube)
{
    const scenes::spec::Scene s = scenes::spec::makeVoronoi(90);
    ASSERT_EQ(s.hulls.size(), 90u);
    double volume = 0.0;
    for (const scenes::spec::BodySpec& b : s.bodies) {
        if (b.shape != scenes::spec::ShapeKind::Hull) continue;
        EXPECT_GT(b.mass, 0.0f);
        EXPECT_GE(s.hulls[size_t(b.hull)].points.size(), 12u);  // at least a tetrahedron
        volume += b.mass;  // mass = volume
    }
    EXPECT_NEAR(volume, 8.0, 1e-4);  // the 2 m cube
}

}  // namespace
}  // namespace btgpu::test
