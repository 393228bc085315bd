#include "geometry/moments.h"

#include <gtest/gtest.h>

#include <random>

using namespace vqsa;

namespace {

// Exact ∫_T x^i y^j z^k dA by expanding in barycentric coordinates and using
// ∫_T λ0^a λ1^b λ2^c dA = 2 A a! b! c! / (a + b + c + 2)!: independent of the quadrature.
double exact_moment(const Vec3 v[3], int i, int j, int k) {
    double poly[5][5][5] = {};  // coefficients of λ0^a λ1^b λ2^c
    poly[0][0][0] = 1;
    const int exponents[3] = {i, j, k};
    for (int axis = 0; axis < 3; ++axis)
        for (int e = 0; e < exponents[axis]; ++e) {
            double next[5][5][5] = {};
            for (int a = 0; a < 5; ++a)
                for (int b = 0; b < 5; ++b)
                    for (int c = 0; c < 5; ++c) {
                        if (poly[a][b][c] == 0) continue;
                        if (a < 4) next[a + 1][b][c] += poly[a][b][c] * v[0][axis];
                        if (b < 4) next[a][b + 1][c] += poly[a][b][c] * v[1][axis];
                        if (c < 4) next[a][b][c + 1] += poly[a][b][c] * v[2][axis];
                    }
            std::copy(&next[0][0][0], &next[0][0][0] + 125, &poly[0][0][0]);
        }
    auto factorial = [](int n) { double f = 1; for (int m = 2; m <= n; ++m) f *= m; return f; };
    const double area = 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).norm();
    double sum = 0;
    for (int a = 0; a < 5; ++a)
        for (int b = 0; b < 5; ++b)
            for (int c = 0; c < 5; ++c)
                sum += poly[a][b][c] * 2 * area * factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 2);
    return sum;
}

// Brute force: the centroid rule on a 4^6-fold subdivision.
double brute_force_moment(const Vec3 v[3], int i, int j, int k) {
    const int n = 64;
    double sum = 0;
    const double area = 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).norm() / (n * n);
    for (int a = 0; a < n; ++a)
        for (int b = 0; a + b < n; ++b) {
            auto at = [&](double s, double t) { return v[0] + s / n * (v[1] - v[0]) + t / n * (v[2] - v[0]); };
            auto f = [&](const Vec3& p) { return std::pow(p.x(), i) * std::pow(p.y(), j) * std::pow(p.z(), k); };
            sum += area * f((at(a, b) + at(a + 1, b) + at(a, b + 1)) / 3);
            if (a + b + 1 < n) sum += area * f((at(a + 1, b) + at(a + 1, b + 1) + at(a, b + 1)) / 3);
        }
    return sum;
}

}  // namespace

TEST(Moments, MatchExactIntegralsAndBruteForce) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int trial = 0; trial < 20; ++trial) {
        const Vec3 v[3] = {Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng))};
        const Moments m = triangle_moments(v[0], v[1], v[2]);
        for (int d = 0; d <= 4; ++d)
            for (int i = d; i >= 0; --i)
                for (int j = d - i; j >= 0; --j) {
                    const int k = d - i - j;
                    const double exact = exact_moment(v, i, j, k);
                    const double scale = m[0];  // |coordinates| ≤ 1, so |moments| ≤ area
                    EXPECT_NEAR(m[moment_index(i, j, k)], exact, 1e-14 * scale) << i << j << k;
                    if (trial < 3) EXPECT_NEAR(m[moment_index(i, j, k)], brute_force_moment(v, i, j, k), 2e-3 * scale);
                }
    }
}

TEST(Moments, IndexOrderStartsWithQuadricMonomials) {
    const int expected[10][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0},
                                 {1, 1, 0}, {1, 0, 1}, {0, 2, 0}, {0, 1, 1}, {0, 0, 2}};
    for (int n = 0; n < 10; ++n) EXPECT_EQ(moment_index(expected[n][0], expected[n][1], expected[n][2]), n);
    EXPECT_EQ(moment_index(0, 0, 4), kMomentCount - 1);
}

TEST(Moments, ShiftAndScaleEqualMomentsOfTheMovedTriangle) {
    const Vec3 a(0.3, -0.2, 0.5), b(0.9, 0.1, 0.4), c(0.2, 0.7, -0.3), center(0.1, 0.2, -0.4);
    const double scale = 0.37;
    const Moments shifted = shifted_moments(triangle_moments(a, b, c), center, scale);
    // Moving the triangle by (p - center)/scale scales its area by 1/scale²; shifted_moments keeps dA.
    const Moments direct = triangle_moments((a - center) / scale, (b - center) / scale, (c - center) / scale);
    for (int n = 0; n < kMomentCount; ++n) EXPECT_NEAR(shifted[n], direct[n] * scale * scale, 1e-12 * std::abs(direct[n]) + 1e-14);
}

TEST(Moments, SumOverRegionIsAdditive) {
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(1, 1, 0), d(0, 1, 0);
    Moments sum = triangle_moments(a, b, c);
    add_to(sum, triangle_moments(a, c, d));
    EXPECT_NEAR(sum[0], 1.0, 1e-15);
    EXPECT_NEAR(sum[moment_index(1, 0, 0)], 0.5, 1e-15);
    EXPECT_NEAR(sum[moment_index(2, 2, 0)], 1.0 / 9, 1e-15);
}
