// Distance between the input surface and the projected surface (docs/METHOD.md §10).
#pragma once

#include "geometry/bvh.h"
#include "geometry/rng.h"
#include "io/mesh.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace vqsa {

struct MetricsOptions {
    // Samples per surface: 0 chooses them for `rms_standard_error` (at least 2 000, at most
    // 500 000); a positive count is taken as is (one pass, no estimate of the error).
    int samples = 0;
    // The relative standard error of the RMS that the sampling aims at (about ±1 % at 95 %).
    double rms_standard_error = 0.005;
    std::uint64_t seed = 7;  // the sampling is reproducible
};

struct Metrics {
    // Symmetric RMS over area-uniform samples of both surfaces, each to the other, and the
    // maximum (Hausdorff) over those samples and every vertex of both, divided by the
    // input's bounding-box diagonal.
    double rms = 0, hausdorff = 0;
    // The estimated relative standard error of `rms` (0 when not estimated) and the
    // samples it rests on (both surfaces).
    double rms_standard_error = 0;
    long samples = 0;
    // The same restricted to each region's samples (both surfaces), and how many fell in
    // it: a region of a few faces may get none, and its figures are then 0 and unmeasured.
    std::vector<double> region_rms, region_hausdorff;
    std::vector<long> region_samples;
    // Distance of every projected vertex to the input surface, relative to the diagonal
    // (the heat map of the browser).
    std::vector<double> vertex_distance;
};

// The measurement in pieces of bounded work (at most `queries_per_step` nearest-point
// queries, or one tree), so a caller can report progress and cancel between them.
// The arrays must outlive the measurement.
class Measurement {
public:
    // `a` and `b` share `triangles` and `labels` (b is a's projection: a sample's own
    // triangle on the other surface bounds its search); `regions` labels in all (labels < 0
    // are left out of the per-region figures).
    Measurement(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const std::vector<Triangle>& triangles,
                const std::vector<int>& labels, int regions, const MetricsOptions& options = {},
                int queries_per_step = 20000);
    // Two unrelated surfaces (no per-region figures).
    Measurement(const std::vector<Vec3>& a, const std::vector<Triangle>& a_triangles, const std::vector<Vec3>& b,
                const std::vector<Triangle>& b_triangles, const MetricsOptions& options = {},
                int queries_per_step = 20000);
    ~Measurement();

    bool step();  // false once finished
    double fraction() const;
    Metrics result() const;

private:
    struct Accumulator;
    struct Sweep;
    struct Surface {
        Surface(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles);
        const std::vector<Vec3>& points;
        const std::vector<Triangle>& triangles;
        std::vector<double> areas;
        std::unique_ptr<TriangleTree> tree;
        std::vector<int> vertex_face;  // a face of each vertex (a search hint), or -1
        // Of each vertex to the other surface, signed: negative behind the nearest triangle.
        std::vector<double> vertex_distance;
        // Sampling density per unit area, per triangle (set_densities); a sample of triangle t
        // weighs its area share over its density share.
        std::vector<double> factor;
        double area = 0, total_density = 0;
        // The area means of the squared distance interpolated linearly from the corners' signed
        // distances, over the surface and over each region: known exactly, so the samples
        // estimate only how far the squared distance departs from it (a control variate).
        double interpolated_mean = 0;
        std::vector<double> region_interpolated_mean;
        double density(std::size_t t) const { return areas[t] * factor[t]; }
        double weight(std::size_t t) const { return total_density / (area * factor[t]); }
    };
    void set_densities();
    void start_sweeps(int samples, std::uint64_t seed);
    long planned_queries() const;
    Accumulator pooled() const;                      // every sweep's samples
    Eigen::Matrix3d pooled_differences() const;     // their successive differences, scaled
    double control_coefficient() const;              // β
    double pooled_standard_error(double beta) const; // of the pooled mean of squared distances

    Surface a_, b_;
    const std::vector<int>* labels_;
    bool shared_;  // b is a's projection
    MetricsOptions options_;
    int queries_per_step_;
    double diagonal_ = 0;
    std::size_t next_vertex_ = 0;  // over a's vertices then b's
    double vertex_max_ = 0;
    std::vector<Accumulator> region_;
    std::vector<std::unique_ptr<Sweep>> sweeps_;  // pairs: a's then b's
    bool extended_ = false;
    long done_queries_ = 0;
};

// Runs a Measurement to its end.
Metrics measure(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const std::vector<Triangle>& triangles,
                const std::vector<int>& labels, int regions, const MetricsOptions& options = {});

// Symmetric RMS and maximum distance between two unrelated surfaces over area-uniform
// samples, over a's bounding-box diagonal (to measure another method's output with the
// same code).
struct SurfaceDistance {
    double rms = 0, hausdorff = 0;
};
SurfaceDistance compare_surfaces(const std::vector<Vec3>& a_points, const std::vector<Triangle>& a_triangles,
                                 const std::vector<Vec3>& b_points, const std::vector<Triangle>& b_triangles,
                                 const MetricsOptions& options = {});

}  // namespace vqsa
