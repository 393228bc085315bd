#include "test_support.h"

#include <cmath>
#include <stdexcept>

namespace vqsa::test {

namespace {

Quadric quadric(double c0, double c1, double c2, double c3, double c4, double c5, double c6, double c7, double c8,
                double c9) {
    Quadric q;
    q.c = {c0, c1, c2, c3, c4, c5, c6, c7, c8, c9};
    return q;
}

}  // namespace

std::vector<Surface> surfaces() {
    const double a = 1.2, b = 0.8, c = 0.5, pi = M_PI;
    const double t30 = std::tan(pi / 6);
    std::vector<Surface> s;
    s.push_back({"plane", QuadricType::plane, quadric(0, 0, 0, 1, 0, 0, 0, 0, 0, 0),
                 [](double u, double v) { return Vec3(u, v, 0); }, -1, 1, -1, 1});
    s.push_back({"sphere", QuadricType::sphere, quadric(-1, 0, 0, 0, 1, 0, 0, 1, 0, 1),
                 [](double t, double p) { return Vec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)); },
                 0, pi, 0, 2 * pi});
    s.push_back({"cylinder", QuadricType::cylinder, quadric(-0.64, 0, 0, 0, 1, 0, 0, 1, 0, 0),
                 [](double t, double z) { return Vec3(0.8 * std::cos(t), 0.8 * std::sin(t), z); }, 0, 2 * pi, -1, 1});
    s.push_back({"cone", QuadricType::cone, quadric(0, 0, 0, 0, 1, 0, 0, 1, 0, -t30 * t30),
                 [t30](double t, double z) { return Vec3(t30 * z * std::cos(t), t30 * z * std::sin(t), z); }, 0, 2 * pi,
                 0.3, 1.5});
    s.push_back({"ellipsoid", QuadricType::ellipsoid, quadric(-1, 0, 0, 0, 1 / (a * a), 0, 0, 1 / (b * b), 0, 1 / (c * c)),
                 [=](double t, double p) {
                     return Vec3(a * std::sin(t) * std::cos(p), b * std::sin(t) * std::sin(p), c * std::cos(t));
                 },
                 0, pi, 0, 2 * pi});
    s.push_back({"hyperboloid_one_sheet", QuadricType::hyperboloid_one_sheet,
                 quadric(-1, 0, 0, 0, 1 / (a * a), 0, 0, 1 / (b * b), 0, -1 / (c * c)),
                 [=](double t, double h) {
                     return Vec3(a * std::cosh(h) * std::cos(t), b * std::cosh(h) * std::sin(t), c * std::sinh(h));
                 },
                 0, 2 * pi, -1.2, 1.2});
    s.push_back({"hyperboloid_two_sheets", QuadricType::hyperboloid_two_sheets,
                 quadric(-1, 0, 0, 0, -1 / (a * a), 0, 0, -1 / (b * b), 0, 1 / (c * c)),
                 [=](double t, double h) {
                     return Vec3(a * std::sinh(h) * std::cos(t), b * std::sinh(h) * std::sin(t), c * std::cosh(h));
                 },
                 0, 2 * pi, 0, 1.2});
    s.push_back({"elliptic_paraboloid", QuadricType::elliptic_paraboloid,
                 quadric(0, 0, 0, -1, 1 / (a * a), 0, 0, 1 / (b * b), 0, 0),
                 [=](double x, double y) { return Vec3(x, y, x * x / (a * a) + y * y / (b * b)); }, -1, 1, -1, 1});
    s.push_back({"hyperbolic_paraboloid", QuadricType::hyperbolic_paraboloid,
                 quadric(0, 0, 0, -1, 1 / (a * a), 0, 0, -1 / (b * b), 0, 0),
                 [=](double x, double y) { return Vec3(x, y, x * x / (a * a) - y * y / (b * b)); }, -1, 1, -1, 1});
    s.push_back({"elliptic_cylinder", QuadricType::elliptic_cylinder, quadric(-1, 0, 0, 0, 1 / (a * a), 0, 0, 1 / (b * b), 0, 0),
                 [=](double t, double z) { return Vec3(a * std::cos(t), b * std::sin(t), z); }, 0, 2 * pi, -1, 1});
    s.push_back({"hyperbolic_cylinder", QuadricType::hyperbolic_cylinder,
                 quadric(-1, 0, 0, 0, 1 / (c * c), 0, 0, -1 / (b * b), 0, 0),
                 [=](double h, double z) { return Vec3(c * std::cosh(h), b * std::sinh(h), z); }, -1.2, 1.2, -1, 1});
    s.push_back({"parabolic_cylinder", QuadricType::parabolic_cylinder, quadric(0, 0, 0, -1, 1 / a, 0, 0, 0, 0, 0),
                 [=](double x, double y) { return Vec3(x, y, x * x / a); }, -1, 1, -1, 1});
    s.push_back({"elliptic_cone", QuadricType::elliptic_cone, quadric(0, 0, 0, 0, 1 / (a * a), 0, 0, 1 / (b * b), 0, -1),
                 [=](double t, double z) { return Vec3(a * z * std::cos(t), b * z * std::sin(t), z); }, 0, 2 * pi, 0.3, 1.2});
    return s;
}

Eigen::Matrix3d random_rotation(std::mt19937& rng) {
    std::normal_distribution<double> n(0, 1);
    return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

Quadric moved(const Quadric& f, const Eigen::Matrix3d& R, const Vec3& t) {
    // p = Rᵀ (q - t): A' = R A Rᵀ, b' = R b - 2 A' t, c' = c - bᵀ Rᵀ t + tᵀ A' t
    const Eigen::Matrix3d A = R * f.A() * R.transpose();
    const Vec3 b = R * f.b();
    return Quadric::from(A, b - 2 * A * t, f.c[0] - b.dot(t) + t.dot(A * t));
}

std::string shared_mesh(const std::string& name) { return std::string(VQSA_SHARED_MESHES) + "/" + name; }

Options with_proxies(int count, std::uint64_t seed) {
    Options o;
    o.lloyd.proxies = count;
    o.lloyd.seed = seed;
    return o;
}

std::string invalid_argument_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

Result approximate(const Mesh& mesh, const Options& options, const ProgressCallback& progress) {
    Pipeline pipeline(mesh, options);
    pipeline.run(progress);
    return pipeline.result();
}

}  // namespace vqsa::test
