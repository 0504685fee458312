// voronoi_spec.cpp — BenchmarkDemo's test 8 as plain data (scene_specs.h, makeVoronoi): the
// Voronoi cells of sites on a Halton sequence in a 2 m cube, each cut out as the intersection
// of its half-spaces (bisector planes of its nearest sites and the cube's faces), with the
// vertices found by intersecting plane triples.
#include "scene_specs.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace btgpu::scenes::spec {

namespace {

using Vec = std::array<double, 3>;
struct PlaneEq {
    Vec n;     // outward
    double d;  // points x inside when n.x <= d
};

double halton(int index, int base)
{
    double f = 1.0, r = 0.0;
    for (int i = index; i > 0; i /= base) {
        f /= base;
        r += f * (i % base);
    }
    return r;
}

double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec cross(const Vec& a, const Vec& b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// The cell's vertices: every point where three of its planes meet and no plane excludes.
std::vector<Vec> cellVertices(const std::vector<PlaneEq>& planes)
{
    std::vector<Vec> out;
    const int n = int(planes.size());
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            for (int k = j + 1; k < n; ++k) {
                const Vec& a = planes[i].n;
                const Vec& b = planes[j].n;
                const Vec& c = planes[k].n;
                const Vec bc = cross(b, c), ca = cross(c, a), ab = cross(a, b);
                const double det = dot(a, bc);
                if (std::fabs(det) < 1e-9) continue;
                Vec x;
                for (int e = 0; e < 3; ++e) x[e] = (planes[i].d * bc[e] + planes[j].d * ca[e] + planes[k].d * ab[e]) / det;
                bool inside = true;
                for (const PlaneEq& p : planes)
                    if (dot(p.n, x) > p.d + 1e-9) {
                        inside = false;
                        break;
                    }
                if (!inside) continue;
                bool dup = false;
                for (const Vec& v : out)
                    if (std::fabs(v[0] - x[0]) + std::fabs(v[1] - x[1]) + std::fabs(v[2] - x[2]) < 1e-6) dup = true;
                if (!dup) out.push_back(x);
            }
    return out;
}

// Volume of the convex cell (m^3): tetrahedra from the centroid to each plane's face polygon,
// the polygon ordered by angle about its plane normal.
double cellVolume(const std::vector<Vec>& verts, const std::vector<PlaneEq>& planes, const Vec& centroid)
{
    double volume = 0.0;
    for (const PlaneEq& p : planes) {
        std::vector<Vec> face;
        for (const Vec& v : verts)
            if (std::fabs(dot(p.n, v) - p.d) < 1e-7) face.push_back(v);
        if (face.size() < 3) continue;
        Vec fc{0, 0, 0};
        for (const Vec& v : face)
            for (int e = 0; e < 3; ++e) fc[e] += v[e] / face.size();
        const Vec u0{face[0][0] - fc[0], face[0][1] - fc[1], face[0][2] - fc[2]};
        const Vec u1 = cross(p.n, u0);
        std::sort(face.begin(), face.end(), [&](const Vec& a, const Vec& b) {
            const Vec da{a[0] - fc[0], a[1] - fc[1], a[2] - fc[2]}, db{b[0] - fc[0], b[1] - fc[1], b[2] - fc[2]};
            return std::atan2(dot(da, u1), dot(da, u0)) < std::atan2(dot(db, u1), dot(db, u0));
        });
        const double h = p.d - dot(p.n, centroid);  // centroid's distance below the plane
        double area = 0.0;
        for (size_t i = 0; i < face.size(); ++i) {
            const Vec& a = face[i];
            const Vec& b = face[(i + 1) % face.size()];
            const Vec c = cross({a[0] - fc[0], a[1] - fc[1], a[2] - fc[2]}, {b[0] - fc[0], b[1] - fc[1], b[2] - fc[2]});
            area += 0.5 * dot(c, p.n);
        }
        volume += area * h / 3.0;
    }
    return volume;
}

}  // namespace

Scene makeVoronoi(int cells)
{
    Scene s;
    s.name = "voronoi " + std::to_string(cells);
    s.iterations = 20;
    BodySpec ground;
    ground.shape = ShapeKind::Plane;
    ground.friction = 0.6f;
    s.bodies.push_back(ground);

    const double half = 1.0;  // the cube [-1, 1] x [0, 2] x [-1, 1]
    std::vector<Vec> sites;
    for (int i = 1; i <= cells; ++i)
        sites.push_back({(2 * halton(i, 2) - 1) * half, 2 * halton(i, 3) * half, (2 * halton(i, 5) - 1) * half});
    const double fallHeight = 3.5;
    for (int c = 0; c < cells; ++c) {
        std::vector<int> order;
        for (int j = 0; j < cells; ++j)
            if (j != c) order.push_back(j);
        auto dist2 = [&](int j) {
            double d = 0;
            for (int e = 0; e < 3; ++e) d += (sites[j][e] - sites[c][e]) * (sites[j][e] - sites[c][e]);
            return d;
        };
        // Every other site's bisector (a cut to the nearest few misses faces: checked by the
        // cells' volumes summing to the cube's); O(cells^4) work, 0.3 s for 90 cells.
        std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return dist2(a) < dist2(b); });
        std::vector<PlaneEq> planes = {{{1, 0, 0}, half}, {{-1, 0, 0}, half}, {{0, 1, 0}, 2 * half},
                                       {{0, -1, 0}, 0},   {{0, 0, 1}, half},  {{0, 0, -1}, half}};
        for (int j : order) {
            Vec n{sites[j][0] - sites[c][0], sites[j][1] - sites[c][1], sites[j][2] - sites[c][2]};
            const double len = std::sqrt(dot(n, n));
            for (double& e : n) e /= len;
            const Vec mid{0.5 * (sites[j][0] + sites[c][0]), 0.5 * (sites[j][1] + sites[c][1]),
                          0.5 * (sites[j][2] + sites[c][2])};
            planes.push_back({n, dot(n, mid)});
        }
        const std::vector<Vec> verts = cellVertices(planes);
        if (verts.size() < 4) continue;
        Vec centroid{0, 0, 0};
        for (const Vec& v : verts)
            for (int e = 0; e < 3; ++e) centroid[e] += v[e] / verts.size();
        HullSpec hull;
        for (const Vec& v : verts)
            for (int e = 0; e < 3; ++e) hull.points.push_back(float(v[e] - centroid[e]));
        BodySpec b;
        b.shape = ShapeKind::Hull;
        b.hull = int(s.hulls.size());
        b.mass = float(cellVolume(verts, planes, centroid));
        b.friction = 0.6f;
        b.pos[0] = float(centroid[0]);
        b.pos[1] = float(centroid[1] + fallHeight);
        b.pos[2] = float(centroid[2]);
        s.hulls.push_back(std::move(hull));
        s.bodies.push_back(b);
    }
    return s;
}

}  // namespace btgpu::scenes::spec
