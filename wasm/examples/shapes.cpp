#include "shapes.h"

#include "geometry/portable_math.h"

#include <cmath>

namespace vqsa {

namespace {

Shape finish(const PolygonSoup& soup, const std::vector<int>& soup_patch) {
    Shape shape;
    shape.mesh = build_mesh(soup);
    shape.patch.reserve(shape.mesh.triangles.size());
    for (int source : shape.mesh.source_face) shape.patch.push_back(soup_patch[source]);
    return shape;
}

}  // namespace

void add_segment(std::vector<ProfilePoint>& profile, double r1, double z1, int steps, int patch) {
    const ProfilePoint start = profile.back();
    for (int i = 1; i <= steps; ++i) {
        const double t = double(i) / steps;
        profile.push_back({start.r + t * (r1 - start.r), start.z + t * (z1 - start.z), patch});
    }
}

void add_arc(std::vector<ProfilePoint>& profile, double rc, double zc, double radius, double a0, double a1, int steps,
             int patch) {
    for (int i = 1; i <= steps; ++i) {
        const double a = a0 + (a1 - a0) * i / steps;
        // Exact zero on the axis, so that the pole welds into one vertex.
        double r = rc + radius * portable::cos(a);
        if (std::abs(r) < 1e-12 * radius) r = 0;
        profile.push_back({r, zc + radius * portable::sin(a), patch});
    }
}

Shape revolve(const std::vector<ProfilePoint>& profile, int around) {
    PolygonSoup soup;
    const int rows = static_cast<int>(profile.size());
    for (const ProfilePoint& p : profile)
        for (int j = 0; j < around; ++j) {
            const double a = 2 * M_PI * j / around;
            soup.positions.emplace_back(p.r * portable::cos(a), p.r * portable::sin(a), p.z);
        }
    std::vector<int> patch;
    for (int i = 0; i + 1 < rows; ++i)
        for (int j = 0; j < around; ++j) {
            const int a = i * around + j, b = i * around + (j + 1) % around;
            const int c = a + around, d = b + around;
            const int t1[3] = {a, b, d}, t2[3] = {a, d, c};
            soup.add_polygon(t1, 3);
            soup.add_polygon(t2, 3);
            patch.push_back(profile[i + 1].patch);
            patch.push_back(profile[i + 1].patch);
        }
    return finish(soup, patch);
}

Shape make_capsule(double radius, double length, int around, int rings) {
    std::vector<ProfilePoint> profile{{0, -length / 2 - radius, 2}};
    add_arc(profile, 0, -length / 2, radius, -M_PI / 2, 0, rings, 2);
    add_segment(profile, radius, length / 2, std::max(1, static_cast<int>(rings * length / (radius * M_PI / 2))), 0);
    add_arc(profile, 0, length / 2, radius, 0, M_PI / 2, rings, 1);
    return revolve(profile, around);
}

Shape make_closed_cylinder(double radius, double height, int around, int rings) {
    std::vector<ProfilePoint> profile{{0, -height / 2, 2}};
    add_segment(profile, radius, -height / 2, rings, 2);
    add_segment(profile, radius, height / 2, std::max(1, static_cast<int>(rings * height / radius)), 0);
    add_segment(profile, 0, height / 2, rings, 1);
    return revolve(profile, around);
}

Shape make_grid(const std::function<Vec3(double, double)>& surface, double u0, double u1, double v0, double v1, int nu,
                int nv) {
    PolygonSoup soup;
    for (int i = 0; i <= nu; ++i)
        for (int j = 0; j <= nv; ++j) soup.positions.push_back(surface(u0 + (u1 - u0) * i / nu, v0 + (v1 - v0) * j / nv));
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const int a = i * (nv + 1) + j, b = a + 1, c = a + nv + 1, d = c + 1;
            const int t1[3] = {a, c, d}, t2[3] = {a, d, b};
            soup.add_polygon(t1, 3);
            soup.add_polygon(t2, 3);
        }
    return finish(soup, std::vector<int>(2 * std::size_t(nu) * nv, 0));
}

void append(PolygonSoup& soup, const Mesh& mesh, const Vec3& offset) {
    const int base = static_cast<int>(soup.positions.size());
    for (const Vec3& p : mesh.vertices) soup.positions.push_back(p + offset);
    for (const Triangle& t : mesh.triangles) {
        const int triangle[3] = {t[0] + base, t[1] + base, t[2] + base};
        soup.add_polygon(triangle, 3);
    }
}

void transform(Mesh& mesh, const Eigen::Matrix3d& rotation, const Vec3& translation) {
    for (Vec3& p : mesh.vertices) p = rotation * p + translation;
}

}  // namespace vqsa
