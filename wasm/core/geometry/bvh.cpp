#include "geometry/bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vqsa {

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    const double denominator = 1 / (va + vb + vc);
    return a + ab * (vb * denominator) + ac * (vc * denominator);
}

TriangleTree::TriangleTree(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles)
    : points_(points), triangles_(triangles) {
    const int n = static_cast<int>(triangles.size());
    order_.resize(n);
    centers_.resize(n);
    for (int i = 0; i < n; ++i) {
        order_[i] = i;
        centers_[i] = (points[triangles[i][0]] + points[triangles[i][1]] + points[triangles[i][2]]) / 3;
    }
    nodes_.reserve(2 * std::max(n, 1));
    if (n > 0) build(0, n);
}

int TriangleTree::build(int first, int count) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    Vec3 clo = lo, chi = hi;
    for (int i = first; i < first + count; ++i) {
        for (int v : triangles_[order_[i]]) lo = lo.cwiseMin(points_[v]), hi = hi.cwiseMax(points_[v]);
        clo = clo.cwiseMin(centers_[order_[i]]), chi = chi.cwiseMax(centers_[order_[i]]);
    }
    nodes_[index].min = lo;
    nodes_[index].max = hi;
    if (count <= 4) {
        nodes_[index].first = first;
        nodes_[index].count = count;
        return index;
    }
    int axis;
    (chi - clo).maxCoeff(&axis);
    const int half = count / 2;
    std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                     [&](int a, int b) {
                         return centers_[a][axis] != centers_[b][axis] ? centers_[a][axis] < centers_[b][axis] : a < b;
                     });
    const int left = build(first, half);
    const int right = build(first + half, count - half);
    nodes_[index].left = left;
    nodes_[index].right = right;
    return index;
}

TriangleTree::Hit TriangleTree::nearest(const Vec3& p) const {
    Hit best{p, std::numeric_limits<double>::infinity(), -1};
    if (nodes_.empty()) return best;
    auto box_distance2 = [&](const Node& node) {
        const Vec3 d = (node.min - p).cwiseMax(p - node.max).cwiseMax(Vec3::Zero());
        return d.squaredNorm();
    };
    double best2 = std::numeric_limits<double>::infinity();
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (box_distance2(node) >= best2) continue;
        if (node.left < 0) {
            for (int i = node.first; i < node.first + node.count; ++i) {
                const Triangle& t = triangles_[order_[i]];
                const Vec3 q = closest_point_on_triangle(p, points_[t[0]], points_[t[1]], points_[t[2]]);
                const double d2 = (q - p).squaredNorm();
                if (d2 < best2) best2 = d2, best = {q, 0, order_[i]};
            }
            continue;
        }
        const int left = node.left, right = node.right;
        // Visit the nearer child first.
        const double dl = box_distance2(nodes_[left]), dr = box_distance2(nodes_[right]);
        if (dl < dr) {
            stack[top++] = right;
            stack[top++] = left;
        } else {
            stack[top++] = left;
            stack[top++] = right;
        }
    }
    best.distance = std::sqrt(best2);
    return best;
}

}  // namespace vqsa
