#include "export/palette.h"

#include <algorithm>
#include <cmath>

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

namespace {

// The sRGB transfer function, inverted: colours are chosen in sRGB, written linear.
double linear_from_srgb(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

}  // namespace

Vec3 region_color(int region) {
    const int id = region % kRegionPaletteSize;
    const double step = id * 0.6180339887498949;
    const double hue = step - std::floor(step);
    const double saturation = 0.55, lightness = id % 2 ? 0.52 : 0.64;
    // HSL to RGB (the CSS formula).
    const double chroma = (1 - std::abs(2 * lightness - 1)) * saturation;
    auto channel = [&](double n) {
        const double k = std::fmod(n + hue * 12, 12.0);
        return lightness - chroma / 2 * std::max(-1.0, std::min({k - 3, 9 - k, 1.0}));
    };
    return {linear_from_srgb(channel(0)), linear_from_srgb(channel(8)), linear_from_srgb(channel(4))};
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
