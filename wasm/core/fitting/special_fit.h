// Geometric (orthogonal-distance) fits of the special types — plane, sphere, circular
// cylinder, circular cone — started from a region's general quadric (ALGORITHM §6).
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

// Exact distance from p to the special surface (plane, sphere, cylinder, cone).
double special_distance(const Classification& shape, const Vec3& p);
// The quadric of a special surface.
Quadric special_quadric(const Classification& shape);

std::optional<SpecialFit> fit_plane_geometric(const Samples& samples);
std::optional<SpecialFit> fit_sphere_geometric(const Samples& samples);
// `axis_guess`: the direction the general quadric suggests for the axis.
std::optional<SpecialFit> fit_cylinder_geometric(const Samples& samples, const Vec3& axis_guess);
std::optional<SpecialFit> fit_cone_geometric(const Samples& samples, const Vec3& axis_guess, const Vec3& apex_guess);

struct SpecialFitOptions {
    // A special type is accepted when its RMS distance is at most (1 + relative) times
    // the general quadric's plus `absolute` (unit frame).
    double relative = 0.25;
    double absolute = 1e-6;
};

// Tries plane, sphere, cylinder and cone, in that order (fewest parameters first), and
// returns the first within tolerance of `general_rms`, if any.
std::optional<SpecialFit> best_special_fit(const Samples& samples, const Quadric& general, double general_rms,
                                           const SpecialFitOptions& options = {});

}  // namespace vqsa
