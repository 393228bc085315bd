#include "io/triangulate.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace vqsa {

namespace {

// Twice the signed area of (a, b, c) in the projection plane: positive where the polygon
// turns the way it runs round.
double turn(const std::array<double, 2>& a, const std::array<double, 2>& b, const std::array<double, 2>& c) {
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

bool in_triangle(const std::array<double, 2>& p, const std::array<double, 2>& a, const std::array<double, 2>& b,
                 const std::array<double, 2>& c) {
    return turn(a, b, p) >= 0 && turn(b, c, p) >= 0 && turn(c, a, p) >= 0;
}

// Ear clipping is quadratic in the vertex count: beyond this a concave polygon is refused
// rather than left to run for minutes.
constexpr std::size_t kMaxConcaveVertices = 4096;

}  // namespace

void triangulate_polygon(const std::vector<Vec3>& points, const int* polygon, std::size_t count,
                         std::vector<Triangle>& out) {
    // A file's triangles come here one by one (millions of them): no allocation for them.
    auto fan = [&](const int* ring, std::size_t n) {
        for (std::size_t k = 1; k + 1 < n; ++k) out.push_back({ring[0], ring[k], ring[k + 1]});
    };
    if (count <= 3) return fan(polygon, count);
    Vec3 normal = Vec3::Zero();  // Newell's: robust for any simple polygon
    for (std::size_t i = 0; i < count; ++i) {
        const Vec3& p = points[polygon[i]];
        const Vec3& q = points[polygon[(i + 1) % count]];
        normal += Vec3((p.y() - q.y()) * (p.z() + q.z()), (p.z() - q.z()) * (p.x() + q.x()),
                       (p.x() - q.x()) * (p.y() + q.y()));
    }
    int drop = 0;
    normal.cwiseAbs().maxCoeff(&drop);
    if (!(std::abs(normal[drop]) > 0)) return fan(polygon, count);  // no area: only degenerate triangles
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    const double orientation = normal[drop] > 0 ? 1 : -1;
    std::vector<std::array<double, 2>> plane(count);
    for (std::size_t i = 0; i < count; ++i)
        plane[i] = {points[polygon[i]][u], orientation * points[polygon[i]][v]};

    // The ring of vertices not yet cut off, as links; an ear is a convex corner whose
    // triangle holds no other vertex (only concave or straight corners can lie in it).
    std::vector<std::size_t> prev(count), next(count);
    for (std::size_t i = 0; i < count; ++i) prev[i] = (i + count - 1) % count, next[i] = (i + 1) % count;
    auto corner = [&](std::size_t b) { return turn(plane[prev[b]], plane[b], plane[next[b]]); };
    bool convex = true;
    for (std::size_t i = 0; i < count && convex; ++i) convex = corner(i) >= 0;
    if (convex) return fan(polygon, count);
    if (count > kMaxConcaveVertices)
        throw std::invalid_argument("a concave polygon of " + std::to_string(count) + " vertices (at most " +
                                    std::to_string(kMaxConcaveVertices) + " are triangulated)");
    auto ear = [&](std::size_t b) {
        const std::size_t a = prev[b], c = next[b];
        if (!(corner(b) > 0)) return false;
        for (std::size_t m = next[c]; m != a; m = next[m])
            if (corner(m) <= 0 && in_triangle(plane[m], plane[a], plane[b], plane[c])) return false;
        return true;
    };
    std::size_t remaining = count, k = 0;
    // Each turn round a simple polygon finds an ear; one without is self-intersecting or
    // collinear to rounding, and the rest goes as a fan.
    for (std::size_t missed = 0; remaining > 3 && missed < remaining;) {
        if (!ear(k)) {
            k = next[k], ++missed;
            continue;
        }
        const std::size_t a = prev[k], c = next[k];
        out.push_back({polygon[a], polygon[k], polygon[c]});
        next[a] = c, prev[c] = a, --remaining;
        k = a, missed = 0;
    }
    std::vector<int> rest;
    for (std::size_t i = 0, m = k; i < remaining; ++i, m = next[m]) rest.push_back(polygon[m]);
    fan(rest.data(), rest.size());
}

}  // namespace vqsa
