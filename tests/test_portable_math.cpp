// The libm substitutes whose bits are the same in every build (geometry/portable_math.h):
// within a few units in the last place of the platform's libm.
#include "geometry/portable_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace vqsa;

namespace {

// |a − b| in units in the last place of b.
double ulps(double a, double b) {
    if (a == b) return 0;
    const double unit = std::nextafter(std::abs(b), INFINITY) - std::abs(b);
    return std::abs(a - b) / unit;
}

}  // namespace

TEST(PortableMath, AgreesWithLibmToAFewUnitsInTheLastPlace) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> exponent(-8, 8), angle(-4 * M_PI, 4 * M_PI);
    double worst_atan = 0, worst_sin = 0, worst_cos = 0, worst_log = 0;
    for (int i = 0; i < 200000; ++i) {
        const double x = std::exp(exponent(rng)) * (i % 2 ? 1 : -1);
        worst_atan = std::max(worst_atan, ulps(portable::atan(x), std::atan(x)));
        worst_log = std::max(worst_log, ulps(portable::log(std::abs(x)), std::log(std::abs(x))));
        const double a = angle(rng);
        // Away from the zeros, where a relative error says nothing of the absolute one.
        if (std::abs(std::sin(a)) > 0.1) worst_sin = std::max(worst_sin, ulps(portable::sin(a), std::sin(a)));
        if (std::abs(std::cos(a)) > 0.1) worst_cos = std::max(worst_cos, ulps(portable::cos(a), std::cos(a)));
    }
    EXPECT_LE(worst_atan, 4);
    EXPECT_LE(worst_sin, 4);
    EXPECT_LE(worst_cos, 4);
    EXPECT_LE(worst_log, 4);
}

TEST(PortableMath, AtanAtItsLimitsAndBranchPoints) {
    EXPECT_EQ(portable::atan(0.0), 0.0);
    EXPECT_EQ(portable::atan(INFINITY), M_PI / 2);
    EXPECT_EQ(portable::atan(-INFINITY), -M_PI / 2);
    EXPECT_TRUE(std::isnan(portable::atan(NAN)));
    for (const double x : {1e-300, 0.26794919243112270647, 1.0, 3.0, 1e300}) {
        EXPECT_EQ(portable::atan(-x), -portable::atan(x)) << x;
        EXPECT_LE(ulps(portable::atan(x), std::atan(x)), 4) << x;
    }
}
