// Fitting a proxy to a region from its moments (docs/METHOD.md §1).
#pragma once

#include "geometry/moments.h"
#include "fitting/quadric.h"

namespace vqsa {

struct FitOptions {
    // The plane is chosen when its mean squared distance is at most
    // (1 + plane_tolerance) times the quadric's: a quadric must earn its extra
    // parameters. Distances below `negligible_distance` (relative to the region's
    // RMS radius) count as zero, so exactly planar regions always get a plane.
    double plane_tolerance = 0.25;
    double negligible_distance = 1e-4;
    // Tikhonov term on Ñ, relative to its mean eigenvalue: keeps the pencil definite
    // for planar and nearly planar regions.
    double regularization = 1e-9;
    // Prefer the plane also where the quadric is a pair of intersecting planes one of which
    // alone holds the region about as well as the plane does (plane_tolerance): m·l = 0 vanishes
    // on l whatever m, and Taubin's fit to a noisy plane tilts m through it so that the
    // first-order distance shaves the noise (two coplanar pieces of a noisy flange's face:
    // their union a quarter to a third below the plane's mean square, typed a pair of
    // planes, and never merged). A union on one part of a degenerate quadric is that part.
    bool plane_of_pair = false;
};

// A region's centroid and RMS radius, from its moments.
struct RegionFrame {
    Vec3 center;
    double radius;
};
RegionFrame region_frame(const Moments& region);

struct Fit {
    Quadric quadric;         // in the moments' frame
    double mean_squared = 0;  // mean squared (first-order) distance to the surface over the region
    // Taubin's fit: the same for the best quadric independent of this one (the pencil's
    // second eigenvalue). About as small, and the region does not determine its quadric (a
    // strip one face wide lies on many). 0 for the plane.
    double next_mean_squared = 0;
};

// Taubin's fit: the generalised eigenvector of the smallest eigenvalue of M s = λ N s,
// with C0 eliminated, solved in region-centred, region-scaled coordinates.
Fit fit_taubin(const Moments& region);

// Among the quadrics through `points` (Taubin's, within a mean squared distance `on`),
// Taubin's fit to `faces`: where the points lie on many quadrics (the two rings of a hole
// one facet deep lie on its cylinder and on the pair of planes through them), the one the
// faces lie on. `next_mean_squared` is the faces' distance to the next one through the
// points (infinite when the points determine the quadric; both infinite when they lie on
// none).
Fit fit_taubin_through(const Moments& points, const Moments& faces, double on);

// The L2-optimal plane (area-weighted principal axes).
Fit fit_plane(const Moments& region);

// The variances of a region's area about its centroid along its principal axes, in
// increasing order: the first is fit_plane's mean squared distance, the second the spread
// across the region's narrower in-plane direction.
Vec3 principal_variances(const Moments& region);

// The better of the two, with the plane preferred as FitOptions says.
Fit fit_region(const Moments& region, const FitOptions& options = {});

}  // namespace vqsa
