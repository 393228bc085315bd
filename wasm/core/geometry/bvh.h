// Nearest-triangle queries on a triangle set: an axis-aligned bounding-box tree.
#pragma once

#include "io/mesh.h"

#include <vector>

namespace vqsa {

// The point of triangle abc nearest to p (Ericson, Real-Time Collision Detection 5.1.5).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

class TriangleTree {
public:
    TriangleTree(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles);

    struct Hit {
        Vec3 point;
        double distance;
        int triangle;
    };
    Hit nearest(const Vec3& p) const;

private:
    struct Node {
        Vec3 min = Vec3::Zero(), max = Vec3::Zero();
        int first = 0, count = 0;  // a leaf's triangles: order_[first, first + count)
        int left = -1, right = -1; // an inner node's children
    };
    int build(int first, int count);

    const std::vector<Vec3>& points_;
    const std::vector<Triangle>& triangles_;
    std::vector<int> order_;
    std::vector<Vec3> centers_;
    std::vector<Node> nodes_;
};

}  // namespace vqsa
