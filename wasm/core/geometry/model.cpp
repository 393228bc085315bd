#include "geometry/model.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vqsa {

namespace {

DualGraph dual_graph(const std::vector<Triangle>& triangles, const std::vector<Vec3>& points) {
    struct EdgeUse {
        std::uint64_t key;
        int face;
        bool operator<(const EdgeUse& o) const { return key != o.key ? key < o.key : face < o.face; }
    };
    const int n = static_cast<int>(triangles.size());
    std::vector<EdgeUse> uses;
    uses.reserve(3 * std::size_t(n));
    for (int f = 0; f < n; ++f)
        for (int k = 0; k < 3; ++k) {
            const std::uint64_t a = triangles[f][k], b = triangles[f][(k + 1) % 3];
            uses.push_back({std::min(a, b) << 32 | std::max(a, b), f});
        }
    std::sort(uses.begin(), uses.end());

    struct Link {
        int from, to;
        double length;
        bool operator<(const Link& o) const { return from != o.from ? from < o.from : to < o.to; }
    };
    std::vector<Link> links;
    links.reserve(uses.size());
    for (std::size_t i = 0; i < uses.size();) {
        std::size_t j = i;
        while (j < uses.size() && uses[j].key == uses[i].key) ++j;
        const int a = static_cast<int>(uses[i].key >> 32), b = static_cast<int>(uses[i].key & 0xffffffffu);
        const double length = (points[a] - points[b]).norm();
        // A fan of many faces on one edge (hostile input) is linked as a ring, not
        // as a clique, to keep the graph linear in size.
        const bool clique = j - i <= 8;
        for (std::size_t p = i; p < j; ++p)
            for (std::size_t q = i; q < j; ++q) {
                if (p == q || uses[p].face == uses[q].face) continue;
                if (clique || q == (p + 1 - i) % (j - i) + i || p == (q + 1 - i) % (j - i) + i)
                    links.push_back({uses[p].face, uses[q].face, length});
            }
        i = j;
    }
    std::sort(links.begin(), links.end());
    // Two faces sharing two edges (folded pairs) are linked once.
    links.erase(std::unique(links.begin(), links.end(),
                            [](const Link& x, const Link& y) { return x.from == y.from && x.to == y.to; }),
                links.end());

    DualGraph graph;
    graph.start.assign(n + 1, 0);
    for (const Link& l : links) ++graph.start[l.from + 1];
    for (int f = 0; f < n; ++f) graph.start[f + 1] += graph.start[f];
    graph.neighbor.reserve(links.size());
    graph.edge_length.reserve(links.size());
    for (const Link& l : links) {
        graph.neighbor.push_back(l.to);
        graph.edge_length.push_back(l.length);
    }
    return graph;
}

}  // namespace

Model make_model(const Mesh& mesh) {
    Model model;
    model.frame = unit_frame(mesh);
    model.points.reserve(mesh.vertices.size());
    for (const Vec3& p : mesh.vertices) model.points.push_back(model.frame.to_unit(p));
    model.triangles = mesh.triangles;
    const std::size_t n = mesh.triangles.size();
    model.barycentres.resize(n);
    model.areas.resize(n);
    model.moments.resize(n);
    for (std::size_t f = 0; f < n; ++f) {
        const Vec3 &a = model.points[mesh.triangles[f][0]], &b = model.points[mesh.triangles[f][1]],
                   &c = model.points[mesh.triangles[f][2]];
        model.barycentres[f] = (a + b + c) / 3.0;
        model.moments[f] = triangle_moments(a, b, c);
        model.areas[f] = model.moments[f][0];
        model.total_area += model.areas[f];
    }
    model.graph = dual_graph(model.triangles, model.points);
    std::vector<Vec3> normal(n);
    for (std::size_t f = 0; f < n; ++f) normal[f] = area_normal(model, static_cast<int>(f)).normalized();
    DualGraph& g = model.graph;
    g.sagitta.resize(g.neighbor.size());
    for (std::size_t f = 0; f < n; ++f)
        for (int e = g.begin(static_cast<int>(f)); e < g.end(static_cast<int>(f)); ++e) {
            const int h = g.neighbor[e];
            // The chord between the unit normals, 2 sin(θ/2): θ to within θ³/24 at the small
            // angles that matter, and no libm call (whose last bits differ in WASM).
            const double turn = std::min((normal[f] - normal[h]).norm(), (normal[f] + normal[h]).norm());
            const double heights = 2 * (model.areas[f] + model.areas[h]) / g.edge_length[e];
            g.sagitta[e] = std::isfinite(turn * heights) ? turn * heights / 16 : 0;
        }
    model.component.assign(model.face_count(), -1);
    auto any = [](auto...) { return true; };
    model.component_count = label_components(model.graph, model.component, 0, any, any);
    return model;
}

std::array<int, 2> shared_edge(const Model& model, int a, int b) {
    std::array<int, 2> shared{-1, -1};
    int k = 0;
    for (int u : model.triangles[a])
        for (int v : model.triangles[b])
            if (u == v && k < 2) shared[k++] = u;
    return k == 2 ? shared : std::array<int, 2>{-1, -1};
}

Vec3 area_normal(const Model& model, int f) {
    const Triangle& t = model.triangles[f];
    return (model.points[t[1]] - model.points[t[0]]).cross(model.points[t[2]] - model.points[t[0]]);
}

bool exactly_coplanar(const Model& model, int f, int h) {
    const Vec3 nf = area_normal(model, f), nh = area_normal(model, h);
    if (!(nf.squaredNorm() > 0 && nh.squaredNorm() > 0)) return false;
    auto off_plane = [&](int a, const Vec3& n, int b) {  // b's far vertex from a's plane
        double d = 0;
        for (int v : model.triangles[b]) d = std::max(d, std::abs((model.points[v] - model.points[model.triangles[a][0]]).dot(n)));
        return d;
    };
    return off_plane(f, nf.normalized(), h) <= kStoredPrecision && off_plane(h, nh.normalized(), f) <= kStoredPrecision;
}

bool coplanar_with_a_neighbour(const Model& model, int f) {
    for (int e = model.graph.begin(f); e < model.graph.end(f); ++e)
        if (exactly_coplanar(model, f, model.graph.neighbor[e])) return true;
    return false;
}

Moments moments_of(const Model& model, const std::vector<int>& faces) {
    Moments sum{};
    for (int f : faces) add_to(sum, model.moments[f]);
    return sum;
}

std::vector<std::pair<int, int>> adjacent_regions(const Model& model, const std::vector<int>& labels) {
    // Per region, its neighbours of higher label: a boundary repeats its pair along its
    // faces, so the repeats are dropped as they come and each list sorted on its own (a
    // partition into a thousand regions asks this after every merge).
    const int regions = labels.empty() ? 0 : *std::max_element(labels.begin(), labels.end()) + 1;
    std::vector<std::vector<int>> above(regions);
    for (int f = 0; f < model.face_count(); ++f)
        for (int e = model.graph.begin(f); e < model.graph.end(f); ++e) {
            const int a = labels[f], b = labels[model.graph.neighbor[e]];
            if (a < b && (above[a].empty() || above[a].back() != b)) above[a].push_back(b);
        }
    std::vector<std::pair<int, int>> pairs;
    for (int a = 0; a < regions; ++a) {
        std::sort(above[a].begin(), above[a].end());
        above[a].erase(std::unique(above[a].begin(), above[a].end()), above[a].end());
        for (int b : above[a]) pairs.emplace_back(a, b);
    }
    return pairs;
}

}  // namespace vqsa
