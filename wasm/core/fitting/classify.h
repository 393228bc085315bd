// Classification of quadrics into the affine taxonomy, with geometric parameters
// (docs/METHOD.md §6). Decisions are made in the frame of the region the quadric stands
// for, so "zero" means negligible at the region's scale.
#pragma once

#include "fitting/quadric.h"

#include <Eigen/Core>

namespace vqsa {

enum class QuadricType {
    plane,
    sphere,
    cylinder,  // circular
    cone,      // circular
    ellipsoid,
    hyperboloid_one_sheet,
    hyperboloid_two_sheets,
    elliptic_paraboloid,
    hyperbolic_paraboloid,
    elliptic_cylinder,
    hyperbolic_cylinder,
    parabolic_cylinder,
    elliptic_cone,
    intersecting_planes,
    parallel_planes,
    empty,  // no real points (fits never produce it on real data, but coefficients can)
};

const char* type_name(QuadricType type);

// Degrees of freedom of a surface of this type in space (pose and shape): 3 for a plane,
// 4 for a sphere, 7 for an elliptic cylinder, 9 for an ellipsoid. Model selection charges
// a fit by this count, so a general quadric that is an elliptic cylinder pays for 7.
int degrees_of_freedom(QuadricType type);

struct ClassifyOptions {
    // An eigenvalue of A is zero when below this fraction of the largest one.
    double zero_eigenvalue = 1e-3;
    // The constant (or the linear term along a zero eigenvalue) is zero when below this
    // fraction of the largest eigenvalue times the region's squared radius (or radius).
    double zero_offset = 1e-3;
    // Curvature below this, relative to the gradient, at the region's scale: a plane.
    double flat = 1e-4;
    // Eigenvalues equal within this relative difference make a sphere, circular
    // cylinder or circular cone.
    double equal_eigenvalues = 1e-2;
};

struct Classification {
    QuadricType type = QuadricType::plane;
    // The centre (ellipsoid, hyperboloids, sphere, parallel planes), vertex
    // (paraboloids), apex (cones), or the point of the axis, line or plane nearest
    // the region's centre (cylinders, intersecting planes, plane).
    Vec3 center = Vec3::Zero();
    // Columns are the principal axes (eigenvectors of A). The distinguished axis
    // (cylinder and cone axis, paraboloid axis, plane normal, the lone-sign axis of a
    // hyperboloid) is column 2.
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    // Semi-axis lengths along the columns of `rotation` (0 where none). Intersecting
    // planes: y0/a = ±y1/b in the frame (a, b up to a common scale); parallel planes:
    // y2 = ±semi_axes[2].
    Vec3 semi_axes = Vec3::Zero();
    double radius = 0;      // sphere, cylinder
    double half_angle = 0;  // cone, radians
    // Cones: the apex lies beyond the region, so the two nappes, which meet only there,
    // are two separate parts of the surface where the region is (the test is the
    // function nappes_apart below).
    bool nappes_apart = false;

    Vec3 axis() const { return rotation.col(2); }
};

// `center` and `radius` describe the region (its centroid and RMS radius) in f's frame.
Classification classify(const Quadric& f, const Vec3& center, double radius, const ClassifyOptions& options = {});

// The same classification in coordinates q = scale * p + translation.
Classification change_frame(const Classification& c, double scale, const Vec3& translation);

// Whether a cone's apex lies beyond a region (centroid, RMS radius): farther from its
// centroid than twice its RMS radius, past the rim of any compact region. There the two
// nappes are apart: a flat cone under noise holds both faces of a plate, one per nappe, as
// a pair of parallel planes would. A region through its apex (a free-form region's
// elliptic cone) is one piece of surface.
bool nappes_apart(const Vec3& apex, const Vec3& region_center, double region_radius);

// The quadrics with two separate parts where their region is (sheets, branches, planes,
// the nappes of a cone whose apex lies beyond the region).
bool has_two_parts(const Classification& c);
// For those, which part a point lies on (+1 or -1), or 0 when it lies within `margin` of
// where the parts separate (the mid-plane of parallel planes or of two sheets, the common
// line of intersecting planes, the gap between branches, the plane through a cone's apex
// across its axis).
int part_of(const Classification& c, const Vec3& p, double margin = 0);

// A region lies on two parts of its quadric when, beyond the margin, both parts hold at
// least `fraction` of its weight and `points` of its points (three: a stray noisy point
// makes no part; exact data may say one is enough). Callers pass a margin of twice the
// region's RMS distance to the quadric.
struct PartWeights {
    double weight[2] = {0, 0};
    int count[2] = {0, 0};
    bool both(double total, double fraction = 1e-3, int points = 3) const {
        const int minor = weight[0] < weight[1] ? 0 : 1;
        return count[minor] >= points && weight[minor] >= fraction * total;
    }
};

}  // namespace vqsa
