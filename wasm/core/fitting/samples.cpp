#include "fitting/samples.h"

#include <algorithm>

namespace vqsa {

Samples vertex_samples(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                       const std::vector<int>& faces) {
    std::vector<int> vertices;
    vertices.reserve(3 * faces.size());
    for (int f : faces)
        for (int v : triangles[f]) vertices.push_back(v);
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    Samples out;
    for (int v : vertices) out.add(points[v], 1.0);
    return out;
}

}  // namespace vqsa
