// Distance between the input surface and the projected surface (docs/METHOD.md §10).
#pragma once

#include "io/mesh.h"

#include <cstdint>
#include <vector>

namespace vqsa {

struct MetricsOptions {
    int samples = 0;          // per surface; 0: twice the face count, at least 20 000, at most 1 000 000
    std::uint64_t seed = 7;   // the sampling is reproducible
};

struct Metrics {
    // Symmetric RMS and maximum (Hausdorff) distance over area-uniform samples of both
    // surfaces, each to the other, divided by the input's bounding-box diagonal.
    double rms = 0, hausdorff = 0;
    // The same restricted to each region's samples (both surfaces).
    std::vector<double> region_rms, region_hausdorff;
    // Distance of every projected vertex to the input surface, relative to the diagonal
    // (the heat map of the browser).
    std::vector<double> vertex_distance;
};

// Symmetric RMS and maximum distance between two unrelated surfaces, over a's
// bounding-box diagonal (to measure another method's output with the same code).
struct SurfaceDistance {
    double rms = 0, hausdorff = 0;
};
SurfaceDistance compare_surfaces(const std::vector<Vec3>& a_points, const std::vector<Triangle>& a_triangles,
                                 const std::vector<Vec3>& b_points, const std::vector<Triangle>& b_triangles,
                                 const MetricsOptions& options = {});

// `a` and `b` share triangles and labels (b is a's projection); `labels` per triangle,
// `regions` labels in all (labels < 0 are left out of the per-region figures).
Metrics measure(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const std::vector<Triangle>& triangles,
                const std::vector<int>& labels, int regions, const MetricsOptions& options = {});

}  // namespace vqsa
