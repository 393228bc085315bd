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
    : TriangleTree(points, triangles, Deferred{}) {
    while (build_some(std::numeric_limits<long>::max())) {
    }
}

TriangleTree::TriangleTree(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles, Deferred)
    : points_(&points), triangles_(&triangles) {
    const int n = static_cast<int>(triangles.size());
    order_.resize(n);
    centers_.resize(n);
    for (int i = 0; i < n; ++i) {
        order_[i] = i;
        centers_[i] = (points[triangles[i][0]] + points[triangles[i][1]] + points[triangles[i][2]]) / 3;
    }
    // Leaves hold 2 to 4 triangles, so there are at most n nodes.
    nodes_.reserve(std::max(n, 1));
    if (n > 0) pending_.push_back({0, n, -1});
    else finish();
}

bool TriangleTree::build_some(long budget) {
    // Depth first, the first child right after its parent: a node's second child is
    // pending while its first subtree is built.
    long spent = 0;
    while (!pending_.empty() && spent < budget) {
        const Range range = pending_.back();
        pending_.pop_back();
        const int index = static_cast<int>(nodes_.size());
        if (range.parent >= 0) nodes_[range.parent].right = index;
        nodes_.push_back({});
        const int first = range.first, count = range.count;
        spent += count;
        Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        Vec3 clo = lo, chi = hi;
        for (int i = first; i < first + count; ++i) {
            for (int v : (*triangles_)[order_[i]]) lo = lo.cwiseMin((*points_)[v]), hi = hi.cwiseMax((*points_)[v]);
            clo = clo.cwiseMin(centers_[order_[i]]), chi = chi.cwiseMax(centers_[order_[i]]);
        }
        nodes_[index].min = lo;
        nodes_[index].max = hi;
        if (count <= 4) {
            nodes_[index].first = first;
            nodes_[index].count = count;
            continue;
        }
        int axis;
        (chi - clo).maxCoeff(&axis);
        const int half = count / 2;
        std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                         [&](int a, int b) {
                             const double ca = centers_[a][axis], cb = centers_[b][axis];
                             return ca != cb ? ca < cb : a < b;
                         });
        pending_.push_back({first + half, count - half, index});
        pending_.push_back({first, half, -1});  // popped next: it becomes node index + 1
    }
    if (!pending_.empty()) return true;
    finish();
    return false;
}

void TriangleTree::finish() {
    centers_ = {};
    const int n = static_cast<int>(order_.size());
    slot_.resize(n);
    for (int i = 0; i < n; ++i) slot_[order_[i]] = i;
    built_ = true;
}

void TriangleTree::visit(const Vec3& p, int slot, double& best2, Hit& best) const {
    const Triangle& t = (*triangles_)[order_[slot]];
    const std::vector<Vec3>& points = *points_;
    const Vec3 q = closest_point_on_triangle(p, points[t[0]], points[t[1]], points[t[2]]);
    const double d2 = (q - p).squaredNorm();
    // Ties go to the lower triangle index, so the answer does not depend on the hint.
    if (d2 < best2 || (d2 == best2 && order_[slot] < best.triangle)) best2 = d2, best = {q, 0, order_[slot]};
}

TriangleTree::Hit TriangleTree::nearest(const Vec3& p, int hint) const {
    Hit best{p, std::numeric_limits<double>::infinity(), -1};
    if (nodes_.empty() || !built_) return best;
    auto box_distance2 = [&](const Node& node) {
        const Vec3 d = (node.min - p).cwiseMax(p - node.max).cwiseMax(Vec3::Zero());
        return d.squaredNorm();
    };
    double best2 = std::numeric_limits<double>::infinity();
    if (hint >= 0 && hint < static_cast<int>(slot_.size())) visit(p, slot_[hint], best2, best);
    // Down the nearer child at once; the farther one waits with its box distance, unless
    // it is already beyond the best (a box at exactly the best distance may hold a tie).
    struct Pending {
        int node;
        double distance2;
    };
    Pending stack[128];
    int top = 0;
    stack[top++] = {0, box_distance2(nodes_[0])};
    while (top > 0) {
        const Pending pending = stack[--top];
        if (pending.distance2 > best2) continue;
        for (int index = pending.node;;) {
            const Node& node = nodes_[index];
            if (node.right < 0) {
                for (int i = node.first; i < node.first + node.count; ++i) visit(p, i, best2, best);
                break;
            }
            const int left = index + 1, right = node.right;
            const double dl = box_distance2(nodes_[left]), dr = box_distance2(nodes_[right]);
            const bool left_first = dl < dr;
            const double near = left_first ? dl : dr, far = left_first ? dr : dl;
            if (far <= best2) stack[top++] = {left_first ? right : left, far};
            if (near > best2) break;
            index = left_first ? left : right;
        }
    }
    best.distance = std::sqrt(best2);
    return best;
}

}  // namespace vqsa
