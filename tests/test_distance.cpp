#include "fitting/distance.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <random>

using namespace vqsa;

namespace {

// Exact distance to a canonical surface by dense sampling of its parametrisation
// followed by Newton refinement of the nearest sample (the squared distance is
// smooth in the parameters near the foot point).
double sampled_distance(const std::function<Vec3(double, double)>& s, double u0, double u1, double v0, double v1,
                        const Vec3& p) {
    const int n = 400;
    double best = std::numeric_limits<double>::infinity(), bu = 0, bv = 0;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const double u = u0 + (u1 - u0) * i / n, v = v0 + (v1 - v0) * j / n;
            const double d = (s(u, v) - p).squaredNorm();
            if (d < best) best = d, bu = u, bv = v;
        }
    // Gauss-Newton on |s(u,v) - p|² with finite differences.
    for (int it = 0; it < 30; ++it) {
        const double h = 1e-6;
        const Vec3 r = s(bu, bv) - p;
        const Vec3 su = (s(bu + h, bv) - s(bu - h, bv)) / (2 * h), sv = (s(bu, bv + h) - s(bu, bv - h)) / (2 * h);
        Eigen::Matrix2d J;
        J << su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv);
        const Eigen::Vector2d g(su.dot(r), sv.dot(r));
        const Eigen::Vector2d step = J.ldlt().solve(-g);
        const double nu = std::clamp(bu + step[0], u0, u1), nv = std::clamp(bv + step[1], v0, v1);
        const double d = (s(nu, nv) - p).squaredNorm();
        if (!(d < best)) break;
        best = d, bu = nu, bv = nv;
    }
    return std::sqrt(best);
}

}  // namespace

TEST(TaubinDistance, NeverExceedsTrueDistanceOnEveryType) {
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 1.0);
    for (const test::Surface& surface : test::surfaces()) {
        int close = 0;
        for (int trial = 0; trial < 40; ++trial) {
            // A point near a random surface point, at up to 0.3 units away.
            std::uniform_real_distribution<double> uu(surface.u0, surface.u1), vv(surface.v0, surface.v1);
            const Vec3 on = surface.point(uu(rng), vv(rng));
            const Vec3 p = on + 0.3 * std::abs(noise(rng)) / 3 * Vec3(noise(rng), noise(rng), noise(rng)).normalized();
            const double truth = sampled_distance(surface.point, surface.u0 - 1, surface.u1 + 1, surface.v0 - 1,
                                                  surface.v1 + 1, p);
            const double taubin = taubin_distance(surface.quadric, p);
            EXPECT_LE(taubin, truth * (1 + 1e-6) + 1e-9) << surface.name;
            // ... and it is a close approximation near the surface (it would be useless otherwise).
            if (truth < 0.05) {
                EXPECT_GE(taubin, 0.7 * truth) << surface.name;
                ++close;
            }
        }
        EXPECT_GT(close, 0) << surface.name;
    }
}

TEST(TaubinDistance, EqualsTheDistanceForPlanesAndIgnoresScaling) {
    const Vec3 n = Vec3(1, 2, -2).normalized();
    const Quadric plane = Quadric::plane(n, Vec3(0.5, 0, 1));
    const Vec3 p(3, -1, 2);
    EXPECT_NEAR(taubin_distance(plane, p), std::abs(n.dot(p - Vec3(0.5, 0, 1))), 1e-14);

    for (const test::Surface& surface : test::surfaces()) {
        Quadric scaled = surface.quadric;
        for (double& c : scaled.c) c *= -37.5;
        const Vec3 q(0.3, -0.7, 0.2);
        EXPECT_NEAR(taubin_distance(scaled, q), taubin_distance(surface.quadric, q), 1e-12) << surface.name;
    }
}

TEST(TriangleError, IsAreaTimesMeanSquaredDistanceOfFourPoints) {
    const Quadric plane = Quadric::plane(Vec3(0, 0, 1), Vec3::Zero());
    const Vec3 a(0, 0, 1), b(2, 0, 1), c(0, 2, 1);
    // Every sample is at distance 1; the area is 2.
    EXPECT_DOUBLE_EQ(triangle_error(plane, 0, a, b, c, (a + b + c) / 3, 2.0), 2.0);
}
