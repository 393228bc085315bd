#include "post/metrics.h"

#include "geometry/bvh.h"
#include "geometry/rng.h"

#include <algorithm>
#include <cmath>

namespace vqsa {

namespace {

struct Accumulator {
    double sum2 = 0, max = 0;
    long count = 0;
    void add(double d) {
        sum2 += d * d;
        max = std::max(max, d);
        ++count;
    }
};

// Area-uniform samples of `from`, each measured against the tree of the other surface.
void sample_distances(const std::vector<Vec3>& from, const std::vector<Triangle>& triangles,
                      const std::vector<int>* labels, const TriangleTree& to, int samples, std::uint64_t seed,
                      Accumulator& total, std::vector<Accumulator>& regions) {
    std::vector<double> cumulative(triangles.size());
    double area = 0;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const Vec3 &a = from[triangles[t][0]], &b = from[triangles[t][1]], &c = from[triangles[t][2]];
        area += 0.5 * (b - a).cross(c - a).norm();
        cumulative[t] = area;
    }
    if (!(area > 0)) return;
    SplitMix64 rng(seed);
    auto uniform = [&] { return (rng.next() >> 11) * (1.0 / 9007199254740992.0); };
    for (int i = 0; i < samples; ++i) {
        const std::size_t t = std::min<std::size_t>(
            std::upper_bound(cumulative.begin(), cumulative.end(), uniform() * area) - cumulative.begin(),
            triangles.size() - 1);
        const double r1 = std::sqrt(uniform()), r2 = uniform();
        const Vec3 p = (1 - r1) * from[triangles[t][0]] + r1 * (1 - r2) * from[triangles[t][1]] +
                       r1 * r2 * from[triangles[t][2]];
        const double d = to.nearest(p).distance;
        total.add(d);
        if (labels && (*labels)[t] >= 0) regions[(*labels)[t]].add(d);
    }
}

double diagonal_of(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles) {
    BoundingBox box;
    for (const Triangle& t : triangles)
        for (int v : t) box.min = box.min.cwiseMin(points[v]), box.max = box.max.cwiseMax(points[v]);
    return box.diagonal();
}

int sample_count(const MetricsOptions& options, std::size_t triangles) {
    return options.samples > 0 ? options.samples
                               : static_cast<int>(std::clamp<std::size_t>(2 * triangles, 20000, 1000000));
}

}  // namespace

SurfaceDistance compare_surfaces(const std::vector<Vec3>& a_points, const std::vector<Triangle>& a_triangles,
                                 const std::vector<Vec3>& b_points, const std::vector<Triangle>& b_triangles,
                                 const MetricsOptions& options) {
    const TriangleTree tree_a(a_points, a_triangles), tree_b(b_points, b_triangles);
    Accumulator total;
    std::vector<Accumulator> none;
    sample_distances(a_points, a_triangles, nullptr, tree_b, sample_count(options, a_triangles.size()), options.seed,
                     total, none);
    sample_distances(b_points, b_triangles, nullptr, tree_a, sample_count(options, a_triangles.size()), options.seed + 1,
                     total, none);
    const double diagonal = diagonal_of(a_points, a_triangles);
    const double scale = diagonal > 0 ? 1 / diagonal : 0;
    return {total.count ? std::sqrt(total.sum2 / total.count) * scale : 0, total.max * scale};
}

Metrics measure(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const std::vector<Triangle>& triangles,
                const std::vector<int>& labels, int regions, const MetricsOptions& options) {
    const double diagonal = diagonal_of(a, triangles);
    const int samples = sample_count(options, triangles.size());
    const TriangleTree tree_a(a, triangles), tree_b(b, triangles);
    Accumulator total;
    std::vector<Accumulator> per_region(regions);
    sample_distances(a, triangles, &labels, tree_b, samples, options.seed, total, per_region);
    sample_distances(b, triangles, &labels, tree_a, samples, options.seed + 1, total, per_region);

    Metrics m;
    const double scale = diagonal > 0 ? 1 / diagonal : 0;
    m.rms = total.count ? std::sqrt(total.sum2 / total.count) * scale : 0;
    m.hausdorff = total.max * scale;
    for (const Accumulator& r : per_region) {
        m.region_rms.push_back(r.count ? std::sqrt(r.sum2 / r.count) * scale : 0);
        m.region_hausdorff.push_back(r.max * scale);
    }
    m.vertex_distance.resize(b.size());
    for (std::size_t v = 0; v < b.size(); ++v) m.vertex_distance[v] = tree_a.nearest(b[v]).distance * scale;
    return m;
}

}  // namespace vqsa
