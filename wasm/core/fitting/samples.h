// Weighted points standing for a region, for the orthogonal-distance fits.
#pragma once

#include "io/mesh.h"

#include <vector>

namespace vqsa {

// Weighted points standing for a region: each face's three vertices and barycentre,
// each weighted by a quarter of its area (the samples of the triangle error, §1).
struct Samples {
    std::vector<Vec3> points;
    std::vector<double> weights;
    double total_weight = 0;
    void add(const Vec3& p, double w) {
        points.push_back(p);
        weights.push_back(w);
        total_weight += w;
    }
};

}  // namespace vqsa
