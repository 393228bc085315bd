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
    // A tree built in pieces: build_some() until it returns false (queries need it built).
    // Either way, the tree refers to the points and triangles: they must outlive it.
    struct Deferred {};
    TriangleTree(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles, Deferred);
    // Builds nodes until about `budget` triangles have been partitioned; false once built.
    bool build_some(long budget);
    bool built() const { return built_; }

    struct Hit {
        Vec3 point;
        double distance;
        int triangle;
    };
    // `hint`: a triangle likely to be near p (or -1). It bounds the search from the start,
    // so a query next to its answer visits a few nodes; the answer does not depend on it.
    Hit nearest(const Vec3& p, int hint = -1) const;

private:
    struct Node {
        Vec3 min = Vec3::Zero(), max = Vec3::Zero();
        int first = 0, count = 0;  // a leaf's triangles: slots [first, first + count)
        int right = -1;            // an inner node's second child (the first follows it)
    };
    struct Range {
        int first, count, parent;  // parent: the node whose second child this is, or -1
    };
    void finish();
    void visit(const Vec3& p, int slot, double& best2, Hit& best) const;

    const std::vector<Vec3>* points_;
    const std::vector<Triangle>* triangles_;
    std::vector<int> order_, slot_;  // slot (tree order) → triangle, triangle → slot
    std::vector<Node> nodes_;
    // While building:
    std::vector<Vec3> centers_;
    std::vector<Range> pending_;
    bool built_ = false;
};

}  // namespace vqsa
