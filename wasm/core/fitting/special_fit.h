// Geometric fits of the special types — plane, sphere, circular cylinder, circular cone by
// orthogonal distances, the elliptic paraboloid by Taubin's — started from a region's
// general quadric (docs/METHOD.md §6).
#pragma once

#include "fitting/classify.h"
#include "fitting/quadric.h"
#include "fitting/samples.h"

#include <optional>

namespace vqsa {

struct SpecialFit {
    Classification shape;  // type, and its parameters
    Quadric quadric;       // the same surface as coefficients (unit norm)
    double rms = 0;        // weighted RMS Euclidean distance of the samples
};

// Distance from p to the special surface: exact for plane, sphere, cylinder and cone,
// Taubin's approximation for the elliptic paraboloid.
double special_distance(const Classification& shape, const Vec3& p);
// The quadric of a special surface.
Quadric special_quadric(const Classification& shape);
// Whether the type has a closed-form distance and foot point (plane, sphere, cylinder, cone).
bool has_closed_form(QuadricType type);

std::optional<SpecialFit> fit_plane_geometric(const Samples& samples);
std::optional<SpecialFit> fit_sphere_geometric(const Samples& samples);
// `axis_guess`: the direction the general quadric suggests for the axis.
std::optional<SpecialFit> fit_cylinder_geometric(const Samples& samples, const Vec3& axis_guess);
std::optional<SpecialFit> fit_cone_geometric(const Samples& samples, const Vec3& axis_guess, const Vec3& apex_guess);
// z = k1 x² + k2 y² (k1, k2 of one sign), started along `axis_guess` or the samples'
// plane's normal; none when the heights over the plane ⊥ `axis_guess` are not elliptic.
std::optional<SpecialFit> fit_paraboloid_geometric(const Samples& samples, const Vec3& axis_guess);

}  // namespace vqsa
