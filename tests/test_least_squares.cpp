// Levenberg–Marquardt on weighted samples (fitting/least_squares.h).
#include "fitting/least_squares.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace vqsa;

namespace {

using Circle = Eigen::Matrix<double, 3, 1>;  // centre x, y and radius of a circle in z = 0

const auto kCircle = [](const Circle& c) {
    return [c](const Vec3& p) { return std::hypot(p.x() - c[0], p.y() - c[1]) - c[2]; };
};

Samples arc(double cx, double cy, double r, double from, double to, int n) {
    Samples s;
    for (int k = 0; k < n; ++k) {
        const double a = from + (to - from) * k / (n - 1);
        s.add({cx + r * std::cos(a), cy + r * std::sin(a), 0}, 1);
    }
    return s;
}

}  // namespace

TEST(LeastSquares, RecoversACircleFromAnOffsetStart) {
    // A quarter arc only, started half a radius off (the fits start from algebraic
    // estimates, no closer than this under noise): the geometric fit lands on the truth.
    const Samples s = arc(1.5, -2, 0.75, 0.2, 1.8, 200);
    const Circle fit = least_squares<3>(s, Circle(1.2, -2.3, 1.1), kCircle, 1);
    EXPECT_NEAR(fit[0], 1.5, 1e-7);
    EXPECT_NEAR(fit[1], -2, 1e-7);
    EXPECT_NEAR(fit[2], 0.75, 1e-7);
}

TEST(LeastSquares, WeightsCount) {
    // Outliers of weight zero do not move the fit; given weight, they do.
    Samples s = arc(0, 0, 1, 0, 2 * M_PI, 100);
    Samples heavy = s;
    for (int k = 0; k < 20; ++k) {
        s.add({3, 3, 0}, 0);
        heavy.add({3, 3, 0}, 1);
    }
    const Circle ignored = least_squares<3>(s, Circle(0.1, 0.1, 1.2), kCircle, 1);
    EXPECT_NEAR(ignored[2], 1, 1e-7);
    EXPECT_NEAR(ignored.head<2>().norm(), 0, 1e-7);
    const Circle moved = least_squares<3>(heavy, Circle(0.1, 0.1, 1.2), kCircle, 1);
    EXPECT_GT(moved.head<2>().norm(), 0.1);
}

TEST(LeastSquares, ThinningKeepsAnEvenSpread) {
    const Samples s = arc(0, 0, 1, 0, 2 * M_PI, 10000);
    const Samples t = thinned(s, 100);
    ASSERT_EQ(t.points.size(), 100u);
    EXPECT_EQ(t.points.front(), s.points.front());
    EXPECT_EQ(t.points[50], s.points[5000]);
    EXPECT_EQ(thinned(t, 1000).points.size(), 100u);  // fewer than the limit: unchanged
}
