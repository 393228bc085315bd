#include "export/palette.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace vqsa {

Vec3 type_color(QuadricType type) {
    switch (type) {
        case QuadricType::plane: return {0.55, 0.62, 0.72};
        case QuadricType::sphere: return {0.90, 0.30, 0.25};
        case QuadricType::cylinder: return {0.30, 0.70, 0.35};
        case QuadricType::cone: return {0.95, 0.60, 0.20};
        case QuadricType::ellipsoid: return {0.60, 0.40, 0.80};
        case QuadricType::hyperboloid_one_sheet: return {0.20, 0.65, 0.70};
        case QuadricType::hyperboloid_two_sheets: return {0.10, 0.45, 0.55};
        case QuadricType::elliptic_paraboloid: return {0.90, 0.80, 0.25};
        case QuadricType::hyperbolic_paraboloid: return {0.65, 0.65, 0.20};
        case QuadricType::elliptic_cylinder: return {0.55, 0.80, 0.45};
        case QuadricType::hyperbolic_cylinder: return {0.90, 0.50, 0.65};
        case QuadricType::parabolic_cylinder: return {0.65, 0.45, 0.30};
        case QuadricType::elliptic_cone: return {0.95, 0.75, 0.45};
        case QuadricType::intersecting_planes: return {0.40, 0.40, 0.45};
        case QuadricType::parallel_planes: return {0.70, 0.70, 0.75};
        case QuadricType::empty: return {0.10, 0.10, 0.10};
    }
    return {0.5, 0.5, 0.5};
}

Vec3 oklab(const Vec3& rgb) {
    const double l = std::cbrt(0.4122214708 * rgb.x() + 0.5363325363 * rgb.y() + 0.0514459929 * rgb.z());
    const double m = std::cbrt(0.2119034982 * rgb.x() + 0.6806995451 * rgb.y() + 0.1073969566 * rgb.z());
    const double s = std::cbrt(0.0883024619 * rgb.x() + 0.2817188376 * rgb.y() + 0.6299787005 * rgb.z());
    return {0.2104542553 * l + 0.7936177850 * m - 0.0040720468 * s,
            1.9779984951 * l - 2.4285922050 * m + 0.4505937099 * s,
            0.0259040371 * l + 0.7827717662 * m - 0.8086757660 * s};
}

namespace {

constexpr double kLightnessWeight = 0.5;

}  // namespace

double color_difference(const Vec3& a, const Vec3& b) {
    const Vec3 d = oklab(a) - oklab(b);
    return std::hypot(kLightnessWeight * d.x(), d.y(), d.z());
}

namespace {

// The sRGB transfer function, inverted: colours are chosen in sRGB, written linear.
double linear_from_srgb(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// Each colour as far as possible from all before it (farthest-point order), among the
// sRGB colours light enough to show shading and coloured enough not to pass for the
// unlabelled grey: whatever the region count, the first regions' colours are as far
// apart as a palette of that size allows (by color_difference). Coordinates are
// rounded to 1e-6 so that the order cannot turn on a last bit of cbrt or pow, which the
// native and WASM builds' libraries may round differently.
std::vector<Vec3> region_palette() {
    constexpr int steps = 20;
    std::vector<Vec3> rgb;
    std::vector<std::array<double, 3>> lab;
    for (int r = 0; r <= steps; ++r)
        for (int g = 0; g <= steps; ++g)
            for (int b = 0; b <= steps; ++b) {
                const Vec3 c(linear_from_srgb(double(r) / steps), linear_from_srgb(double(g) / steps),
                             linear_from_srgb(double(b) / steps));
                const Vec3 e = oklab(c);
                const double chroma2 = e.y() * e.y() + e.z() * e.z();
                if (e.x() < 0.62 || e.x() > 0.82 || chroma2 < 0.08 * 0.08 || chroma2 > 0.18 * 0.18) continue;
                rgb.push_back(c);
                lab.push_back({std::round(kLightnessWeight * e.x() * 1e6), std::round(e.y() * 1e6), std::round(e.z() * 1e6)});
            }
    auto distance2 = [&](std::size_t i, std::size_t j) {
        const double dl = lab[i][0] - lab[j][0], da = lab[i][1] - lab[j][1], db = lab[i][2] - lab[j][2];
        return dl * dl + da * da + db * db;
    };
    // The first: the candidate nearest a muted red, as the first region has always been.
    const Vec3 first = oklab(Vec3(linear_from_srgb(0.84), linear_from_srgb(0.44), linear_from_srgb(0.44)));
    std::size_t next = 0;
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < lab.size(); ++i) {
        const double d = (oklab(rgb[i]) - first).squaredNorm();
        if (d < nearest) nearest = d, next = i;
    }
    std::vector<double> gap(lab.size(), std::numeric_limits<double>::infinity());
    std::vector<Vec3> palette;
    while (static_cast<int>(palette.size()) < kRegionPaletteSize) {
        palette.push_back(rgb[next]);
        for (std::size_t i = 0; i < lab.size(); ++i) gap[i] = std::min(gap[i], distance2(i, next));
        next = static_cast<std::size_t>(std::max_element(gap.begin(), gap.end()) - gap.begin());
    }
    return palette;
}

}  // namespace

Vec3 region_color(int region) {
    static const std::vector<Vec3> palette = region_palette();
    return palette[region % kRegionPaletteSize];
}

nlohmann::json palette_json() {
    nlohmann::json types = nlohmann::json::object();
    for (int t = 0; t <= static_cast<int>(QuadricType::empty); ++t) {
        const Vec3 c = type_color(static_cast<QuadricType>(t));
        types[type_name(static_cast<QuadricType>(t))] = {c.x(), c.y(), c.z()};
    }
    nlohmann::json regions = nlohmann::json::array();
    for (int r = 0; r < kRegionPaletteSize; ++r) {
        const Vec3 c = region_color(r);
        regions.push_back({c.x(), c.y(), c.z()});
    }
    return {{"types", types}, {"regions", regions}};
}

}  // namespace vqsa
