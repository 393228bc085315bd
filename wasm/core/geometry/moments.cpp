#include "geometry/moments.h"

namespace vqsa {

namespace {

struct MomentTable {
    int index[5][5][5];
    int exponent[kMomentCount][3];

    MomentTable() {
        int n = 0;
        for (int d = 0; d <= 4; ++d)
            for (int i = d; i >= 0; --i)
                for (int j = d - i; j >= 0; --j) {
                    const int k = d - i - j;
                    index[i][j][k] = n;
                    exponent[n][0] = i, exponent[n][1] = j, exponent[n][2] = k;
                    ++n;
                }
    }
};

const MomentTable& table() {
    static const MomentTable t;
    return t;
}

// Dunavant's symmetric 6-point rule, exact for polynomials of degree 4.
constexpr double kW1 = 0.22338158967801146570, kA1 = 0.44594849091596488632;
constexpr double kW2 = 0.10995174365532186764, kA2 = 0.09157621350977074346;

constexpr int kBinomial[5][5] = {{1}, {1, 1}, {1, 2, 1}, {1, 3, 3, 1}, {1, 4, 6, 4, 1}};

}  // namespace

int moment_index(int i, int j, int k) { return table().index[i][j][k]; }

Moments point_moments(const Vec3& p, double weight) {
    const MomentTable& t = table();
    double pw[3][5];
    for (int axis = 0; axis < 3; ++axis) {
        pw[axis][0] = 1.0;
        for (int e = 1; e <= 4; ++e) pw[axis][e] = pw[axis][e - 1] * p[axis];
    }
    Moments m;
    for (int n = 0; n < kMomentCount; ++n) m[n] = weight * pw[0][t.exponent[n][0]] * pw[1][t.exponent[n][1]] * pw[2][t.exponent[n][2]];
    return m;
}

Moments triangle_moments(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double weight[2] = {kW1 * area, kW2 * area};
    const double alpha[2] = {kA1, kA2};
    Moments m{};
    for (int rule = 0; rule < 2; ++rule) {
        const double s = alpha[rule], r = 1.0 - 2.0 * s;
        const Vec3 points[3] = {r * a + s * b + s * c, s * a + r * b + s * c, s * a + s * b + r * c};
        for (const Vec3& p : points) add_to(m, point_moments(p, weight[rule]));
    }
    return m;
}

Moments shifted_moments(const Moments& m, const Vec3& center, double scale) {
    const MomentTable& t = table();
    Moments current = m;
    // One axis at a time: ∫ (x - c)^i ... = Σ_a C(i,a) (-c)^(i-a) ∫ x^a ...
    for (int axis = 0; axis < 3; ++axis) {
        double power[5] = {1.0};
        for (int e = 1; e <= 4; ++e) power[e] = power[e - 1] * -center[axis];
        Moments next{};
        for (int n = 0; n < kMomentCount; ++n) {
            int e[3] = {t.exponent[n][0], t.exponent[n][1], t.exponent[n][2]};
            const int top = e[axis];
            double sum = 0.0;
            for (int a = 0; a <= top; ++a) {
                e[axis] = a;
                sum += kBinomial[top][a] * power[top - a] * current[t.index[e[0]][e[1]][e[2]]];
            }
            next[n] = sum;
        }
        current = next;
    }
    double inverse[5] = {1.0};
    for (int d = 1; d <= 4; ++d) inverse[d] = inverse[d - 1] / scale;
    for (int n = 0; n < kMomentCount; ++n)
        current[n] *= inverse[t.exponent[n][0] + t.exponent[n][1] + t.exponent[n][2]];
    return current;
}

}  // namespace vqsa
