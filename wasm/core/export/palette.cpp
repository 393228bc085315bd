#include "export/palette.h"

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

Vec3 region_color(QuadricType type, int region) {
    const double step = region * 0.6180339887498949;
    return type_color(type) * (0.78 + 0.22 * (step - std::floor(step)));
}

}  // namespace vqsa
