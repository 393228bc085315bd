#include "geometry/features.h"

#include "geometry/portable_math.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace vqsa {

double crease_cosine(double crease_angle, double fraction) {
    return portable::cos(fraction * crease_angle * M_PI / 180);
}

namespace {

// +1 or -1 per face so that neighbours traverse their shared edge in opposite
// directions (breadth first from each component's first face; where the mesh is not
// orientable the first choice stays).
std::vector<signed char> orientation(const Model& model) {
    const DualGraph& g = model.graph;
    const int n = model.face_count();
    std::vector<signed char> sign(n, 0);
    auto same_direction = [&](int f, int h) {
        // The edge f and h share: same direction in both means they disagree.
        const Triangle &a = model.triangles[f], &b = model.triangles[h];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (a[i] == b[j] && a[(i + 1) % 3] == b[(j + 1) % 3]) return true;
        return false;
    };
    std::vector<int> queue;
    for (int start = 0; start < n; ++start) {
        if (sign[start]) continue;
        sign[start] = 1;
        queue.assign(1, start);
        for (std::size_t q = 0; q < queue.size(); ++q) {
            const int f = queue[q];
            for (int e = g.begin(f); e < g.end(f); ++e) {
                const int h = g.neighbor[e];
                if (sign[h]) continue;
                sign[h] = static_cast<signed char>(same_direction(f, h) ? -sign[f] : sign[f]);
                queue.push_back(h);
            }
        }
    }
    return sign;
}

// Unit face normals, consistently oriented where the mesh allows.
std::vector<Vec3> face_normals(const Model& model) {
    const int n = model.face_count();
    const std::vector<signed char> sign = orientation(model);
    std::vector<Vec3> normal(n);
    for (int f = 0; f < n; ++f) {
        const Vec3 c = area_normal(model, f);
        const double length = c.norm();
        normal[f] = length > 0 ? Vec3(sign[f] * c / length) : Vec3::Zero();
    }
    return normal;
}

// The upper median; 0 of none.
double median(std::vector<double> x) {
    if (x.empty()) return 0;
    std::nth_element(x.begin(), x.begin() + x.size() / 2, x.end());
    return x[x.size() / 2];
}

// The noise level: the median distance of a vertex from the mean of its neighbours, along
// the normal. `smooth`: over vertices whose faces turn by less than the crease angle (on a
// coarse CAD tessellation most vertices sit on edges, and their deviation is no noise), 0
// when too few are smooth to tell; `all`: over every vertex (noise of the faces' own width
// turns every vertex's faces by more than the crease angle, and leaves none smooth).
struct NoiseLevels {
    double smooth = 0, all = 0;
};

NoiseLevels noise_levels(const Model& model, const std::vector<Vec3>& normal, double crease_angle) {
    const int n = model.face_count();
    std::vector<Vec3> vertex_normal(model.points.size(), Vec3::Zero()), neighbours(model.points.size(), Vec3::Zero());
    std::vector<int> neighbour_count(model.points.size(), 0);
    for (int f = 0; f < n; ++f) {
        const Triangle& t = model.triangles[f];
        for (int i = 0; i < 3; ++i) {
            vertex_normal[t[i]] += model.areas[f] * normal[f];
            neighbours[t[i]] += model.points[t[(i + 1) % 3]] + model.points[t[(i + 2) % 3]];
            neighbour_count[t[i]] += 2;
        }
    }
    const double smooth_cos = crease_cosine(crease_angle);
    std::vector<Vec3> lowest(model.points.size(), Vec3::Zero());  // a face normal per vertex, to compare with
    std::vector<char> smooth(model.points.size(), 1);
    for (int f = 0; f < n; ++f)
        for (int v : model.triangles[f]) {
            if (lowest[v].squaredNorm() == 0) lowest[v] = normal[f];
            else if (normal[f].dot(lowest[v]) < smooth_cos) smooth[v] = 0;
        }
    std::vector<double> smooth_deviations, deviations;
    for (std::size_t v = 0; v < model.points.size(); ++v) {
        if (neighbour_count[v] == 0 || !(vertex_normal[v].norm() > 0)) continue;
        deviations.push_back(std::abs((model.points[v] - neighbours[v] / neighbour_count[v]).dot(vertex_normal[v].normalized())));
        if (smooth[v]) smooth_deviations.push_back(deviations.back());
    }
    NoiseLevels levels;
    levels.all = median(std::move(deviations));
    if (smooth_deviations.size() * 10 >= model.points.size()) levels.smooth = median(std::move(smooth_deviations));
    return levels;
}

// A face's smallest altitude: across its narrowest width.
double narrowest_width(const Model& model, int f) {
    const Triangle& t = model.triangles[f];
    double longest = 0;
    for (int i = 0; i < 3; ++i) longest = std::max(longest, (model.points[t[i]] - model.points[t[(i + 1) % 3]]).norm());
    return longest > 0 ? 2 * model.areas[f] / longest : 0;
}

// Bilateral filtering over edge neighbours: a neighbour counts by how close its normal
// is (half weight at the faces' range), so noise averages out while sharp edges, whose
// two sides barely see each other, stay. Not by area: a large face beside a thin strip
// (the side of a plate) would drag the strip's normal over the crease.
std::vector<Vec3> filter_normals(const DualGraph& g, std::vector<Vec3> normal, const std::vector<double>& range,
                                 int iterations) {
    const int n = static_cast<int>(normal.size());
    std::vector<Vec3> next(n);
    for (int it = 0; it < iterations; ++it) {
        for (int f = 0; f < n; ++f) {
            Vec3 sum = normal[f];
            for (int e = g.begin(f); e < g.end(f); ++e) {
                const int h = g.neighbor[e];
                const double r = std::max(range[f], range[h]);
                sum += std::exp(-std::log(2.0) * (normal[h] - normal[f]).squaredNorm() / (r * r)) * normal[h];
            }
            const double length = sum.norm();
            next[f] = length > 0 ? Vec3(sum / length) : normal[f];
        }
        normal.swap(next);
    }
    return normal;
}

// Per face, the mean normal (by area) of the most consistent patch among those centred
// within `rings` dual rings of it (a patch: the faces within `rings` of its centre; its
// consistency: the length of its faces' mean unit normal), after Zhang et al. 2015,
// "Guided mesh normal filtering": near a crease that patch lies on the face's own side.
// `patch_faces`: per face, the faces of the patch centred on it.
std::vector<Vec3> guidance_normals(const DualGraph& g, const std::vector<Vec3>& normal, const std::vector<double>& area,
                                   int rings, std::vector<int>& patch_faces) {
    const int n = static_cast<int>(normal.size());
    std::vector<Vec3> mean(n);
    std::vector<double> spread(n);
    std::vector<int> stamp(n, -1), ring;
    auto gather = [&](int centre) {
        ring.assign(1, centre);
        stamp[centre] = centre;
        for (int depth = 0, begin = 0; depth < rings; ++depth) {
            const int end = static_cast<int>(ring.size());
            for (int i = begin; i < end; ++i)
                for (int e = g.begin(ring[i]); e < g.end(ring[i]); ++e)
                    if (stamp[g.neighbor[e]] != centre) stamp[g.neighbor[e]] = centre, ring.push_back(g.neighbor[e]);
            begin = end;
        }
    };
    patch_faces.assign(n, 1);
    for (int c = 0; c < n; ++c) {
        gather(c);
        patch_faces[c] = static_cast<int>(ring.size());
        Vec3 sum = Vec3::Zero();
        double total = 0;
        for (int f : ring) sum += area[f] * normal[f], total += area[f];
        mean[c] = sum.norm() > 0 ? Vec3(sum.normalized()) : normal[c];
        spread[c] = total > 0 ? 1 - sum.norm() / total : 1;
    }
    // Each face takes the mean of the most consistent patch centred within `rings` of it,
    // found one ring at a time: the least within k + 1 rings of a face is the least of its
    // own and its neighbours' least within k.
    std::vector<int> best(n), next(n);
    for (int f = 0; f < n; ++f) best[f] = f;
    auto better = [&](int c, int d) { return spread[c] < spread[d] || (spread[c] == spread[d] && c < d); };
    for (int depth = 0; depth < rings; ++depth) {
        for (int f = 0; f < n; ++f) {
            next[f] = best[f];
            for (int e = g.begin(f); e < g.end(f); ++e)
                if (better(best[g.neighbor[e]], next[f])) next[f] = best[g.neighbor[e]];
        }
        best.swap(next);
    }
    std::vector<Vec3> guidance(n);
    for (int f = 0; f < n; ++f) guidance[f] = mean[best[f]];
    return guidance;
}

// Per face, whether it keeps its own normal `raw` rather than its patch's mean `guidance`:
// the `wide` faces, and those whose patch lies across a crease from them. A strip one
// triangle wide between wide faces (a slab's side of two triangles) took the mean of a patch
// on the wide face beside it, turned 90° from its own, and with it the slab's top and sides
// fell into one chart. A guidance turned from the face's own normal by more than the crease
// angle, and by more than the noise turns the face, is another face's. Noise turns a face of
// altitude h by about 2σ/h, and by kTiltsAcross times that almost never (the noisy L-bracket
// at detail 3, σ 0.2 %: one of its 38K faces, against 150 beyond three). Not by less than
// the crease angle: on a coarse curved face a patch's mean turns with the surface.
// Such a face takes its neighbours along: those whose guidance is turned beyond the crease
// angle too, and whose own normal lies nearer its own than their guidance. The noise
// criterion alone, on a cylinder's strips beside a flat end, took the wider strips and left
// the narrower on the end's normal between them: 200 charts of a few faces on the noisy pipe
// junction (abc_pipe_junction.stl, σ 0.1 %), 14–31 before, 28–56 so.
std::vector<char> own_normals(const DualGraph& g, const std::vector<Vec3>& raw, const std::vector<Vec3>& guidance,
                              const std::vector<char>& wide, const std::vector<double>& altitude, double noise,
                              double crease_angle) {
    constexpr double kTiltsAcross = 6;
    const int n = static_cast<int>(raw.size());
    const double cos_crease = crease_cosine(crease_angle);
    std::vector<char> own(n, 0);
    std::vector<int> stack;
    for (int f = 0; f < n; ++f) {
        const double noise_turn = kTiltsAcross * 2 * noise / std::max(altitude[f], 1e-300);
        const double cosine = guidance[f].dot(raw[f]);
        if (wide[f]) own[f] = 1;
        else if (noise_turn < M_PI && cosine < cos_crease && cosine < portable::cos(noise_turn))
            own[f] = 1, stack.push_back(f);
    }
    while (!stack.empty()) {
        const int f = stack.back();
        stack.pop_back();
        for (int e = g.begin(f); e < g.end(f); ++e) {
            const int h = g.neighbor[e];
            if (own[h] || !(guidance[h].dot(raw[h]) < cos_crease) || !(raw[h].dot(raw[f]) > raw[h].dot(guidance[h])))
                continue;
            own[h] = 1;
            stack.push_back(h);
        }
    }
    return own;
}

// Creases: dual links whose (filtered) normals differ by more than the crease angle.
// Noise leaves spurious creases inside faces: a crease is confirmed only if the mean
// normals of the faces around each side (two rings, not crossing creases) still differ
// by the crease angle.
std::vector<char> find_creases(const DualGraph& g, const std::vector<Vec3>& normal, double crease_angle) {
    const int n = static_cast<int>(normal.size());
    const double cos_limit = crease_cosine(crease_angle);
    std::vector<char> crease(g.neighbor.size(), 0);
    for (int f = 0; f < n; ++f)
        for (int e = g.begin(f); e < g.end(f); ++e)
            crease[e] = crease_angle < 180 && normal[f].dot(normal[g.neighbor[e]]) < cos_limit;
    auto side_normal = [&](int f) {
        Vec3 sum = normal[f];
        std::vector<int> ring{f};
        for (int depth = 0, begin = 0; depth < 2; ++depth) {
            const int end = static_cast<int>(ring.size());
            for (int i = begin; i < end; ++i)
                for (int e = g.begin(ring[i]); e < g.end(ring[i]); ++e) {
                    const int m = g.neighbor[e];
                    if (crease[e] || std::find(ring.begin(), ring.end(), m) != ring.end()) continue;
                    ring.push_back(m);
                    sum += normal[m];
                }
            begin = end;
        }
        return Vec3(sum.normalized());
    };
    std::vector<char> confirmed(crease.size(), 0);
    for (int f = 0; f < n; ++f)
        for (int e = g.begin(f); e < g.end(f); ++e)
            if (crease[e] && f < g.neighbor[e]) confirmed[e] = side_normal(f).dot(side_normal(g.neighbor[e])) < cos_limit;
    for (int f = 0; f < n; ++f)
        for (int e = g.begin(f); e < g.end(f); ++e) {
            const int h = g.neighbor[e];
            if (!crease[e] || f < h) continue;
            for (int k = g.begin(h); k < g.end(h); ++k)
                if (g.neighbor[k] == f) confirmed[e] = confirmed[k];
        }
    return confirmed;
}

// Charts: reliable faces joined by edges that are not creases. Unreliable faces join no
// two faces (a chain of them along a crease would bridge it); afterwards each takes the
// chart of the nearest reliable face, breadth first. But in an `exact` tessellation, whose
// faces no noise turned, unreliable faces joined among themselves and to no reliable one
// (creases all round) are a chart of their own: a tube's end, a wall thick, meshed with
// one row of triangles between its two circles.
void find_charts(const DualGraph& g, const std::vector<char>& reliable, bool exact, Features& out) {
    const int n = static_cast<int>(reliable.size());
    out.chart.assign(n, -1);
    auto not_crease = [&](int, int link) { return !out.crease[link]; };
    out.chart_count = label_components(g, out.chart, 0, [&](int f) { return reliable[f] != 0; }, not_crease);
    if (exact) {
        std::vector<int> piece(n, -1);
        const int pieces = label_components(g, piece, 0, [&](int f) { return !reliable[f]; }, not_crease);
        std::vector<char> joined(pieces, 0);
        for (int f = 0; f < n; ++f)
            for (int e = g.begin(f); e < g.end(f) && piece[f] >= 0; ++e)
                if (!out.crease[e] && reliable[g.neighbor[e]]) joined[piece[f]] = 1;
        out.chart_count = label_components(g, out.chart, out.chart_count,
                                           [&](int f) { return piece[f] >= 0 && !joined[piece[f]]; }, not_crease);
    }
    std::vector<int> queue;
    for (int f = 0; f < n; ++f)
        if (out.chart[f] >= 0) queue.push_back(f);
    for (std::size_t q = 0; q < queue.size(); ++q)
        for (int e = g.begin(queue[q]); e < g.end(queue[q]); ++e) {
            const int m = g.neighbor[e];
            if (out.chart[m] < 0) out.chart[m] = out.chart[queue[q]], queue.push_back(m);
        }
    // The components without a reliable face.
    out.chart_count = label_components(g, out.chart, out.chart_count, [](int) { return true; }, not_crease);
}

// Each vertex's roughness: how far it lies, along its normal, from the quadric height
// field z = ax² + bxy + cy² + dx + ey + f fitted to it and its two rings, the residual
// divided by √(1 − leverage) so that under noise σ along the normals it has a standard
// deviation of exactly σ, whatever the tessellation's layout (an umbrella's second
// difference weighs the vertices by their valences, and a clean irregular tessellation
// of a curved surface bends it: neither is noise). A clean surface leaves only its terms
// beyond the quadric. A vertex on a crease is measured once per chart, from that chart's
// faces only: the crease itself is no roughness.
struct VertexDeviations {
    std::vector<int> chart, vertex;  // per measurement
    std::vector<double> magnitude;
};

VertexDeviations vertex_deviations(const Model& model, const std::vector<Vec3>& normal, const Features& out) {
    const int n = model.face_count();
    const std::size_t vn = model.points.size();
    std::vector<int> vertex_chart(vn, -1);  // the chart of a vertex's faces, or -2 for several
    for (int f = 0; f < n; ++f)
        for (int v : model.triangles[f])
            vertex_chart[v] = vertex_chart[v] == -1 || vertex_chart[v] == out.chart[f] ? out.chart[f] : -2;
    std::map<std::pair<int, int>, int> crease_slot;  // (vertex, chart) of crease vertices → slot
    auto slot = [&](int v, int chart) {
        if (vertex_chart[v] != -2) return v;
        const auto [it, added] = crease_slot.try_emplace({v, chart}, static_cast<int>(vn + crease_slot.size()));
        return it->second;
    };
    std::vector<Vec3> slot_normal(vn, Vec3::Zero());
    std::vector<std::vector<int>> ring(vn);  // a slot's neighbouring slots, its chart's faces only
    std::vector<int> slot_vertex(vn), slot_chart(vn, -1);
    for (std::size_t v = 0; v < vn; ++v) slot_vertex[v] = static_cast<int>(v);
    for (int f = 0; f < n; ++f) {
        const Triangle& t = model.triangles[f];
        for (int i = 0; i < 3; ++i) {
            const int k = slot(t[i], out.chart[f]);
            if (k >= static_cast<int>(slot_normal.size())) {
                slot_normal.resize(k + 1, Vec3::Zero()), ring.resize(k + 1), slot_vertex.resize(k + 1), slot_chart.resize(k + 1);
                slot_vertex[k] = t[i];
            }
            slot_chart[k] = out.chart[f];
            slot_normal[k] += model.areas[f] * normal[f];
            for (int j : {(i + 1) % 3, (i + 2) % 3}) {
                const int m = slot(t[j], out.chart[f]);
                if (std::find(ring[k].begin(), ring[k].end(), m) == ring[k].end()) ring[k].push_back(m);
            }
        }
    }
    VertexDeviations out_deviations;
    std::vector<int> mark(ring.size(), -1), support;
    for (std::size_t k = 0; k < ring.size(); ++k) {
        if (slot_chart[k] < 0 || !(slot_normal[k].norm() > 0)) continue;
        support.clear();
        mark[k] = static_cast<int>(k);
        for (int a : ring[k])
            if (mark[a] != static_cast<int>(k)) mark[a] = static_cast<int>(k), support.push_back(a);
        double spacing = 0;  // the nearest ring's mean length: the fit's scale
        for (int a : support) spacing += (model.points[slot_vertex[a]] - model.points[slot_vertex[k]]).norm();
        const std::size_t first = support.size();
        for (std::size_t i = 0; i < first; ++i)
            for (int b : ring[support[i]])
                if (mark[b] != static_cast<int>(k)) mark[b] = static_cast<int>(k), support.push_back(b);
        // More than the six unknowns, with room to tell noise from the fit.
        if (support.size() < 9 || !(spacing > 0)) continue;
        spacing /= static_cast<double>(first);
        const Vec3 z = slot_normal[k].normalized();
        const Vec3 x = z.unitOrthogonal(), y = z.cross(x);
        const Vec3& origin = model.points[slot_vertex[k]];
        Eigen::Matrix<double, 6, 6> normal_matrix = Eigen::Matrix<double, 6, 6>::Zero();
        Eigen::Matrix<double, 6, 1> right = Eigen::Matrix<double, 6, 1>::Zero();
        auto add = [&](const Vec3& p) {
            const Vec3 d = (p - origin) / spacing;
            const double u = d.dot(x), v = d.dot(y);
            Eigen::Matrix<double, 6, 1> row;
            row << u * u, u * v, v * v, u, v, 1;
            normal_matrix.selfadjointView<Eigen::Lower>().rankUpdate(row);
            right += row * d.dot(z);
        };
        add(origin);
        for (int a : support) add(model.points[slot_vertex[a]]);
        const Eigen::Matrix<double, 6, 6> full = normal_matrix.selfadjointView<Eigen::Lower>();
        const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> solver(full);
        // Pivots far apart: the support is no surface patch (its points on a line).
        const auto pivots = solver.vectorD().cwiseAbs();
        if (solver.info() != Eigen::Success || !(pivots.minCoeff() > 1e-9 * pivots.maxCoeff())) continue;
        Eigen::Matrix<double, 6, 1> unit = Eigen::Matrix<double, 6, 1>::Zero();
        unit[5] = 1;
        const double leverage = solver.solve(unit)[5];  // the centre's row is (0, 0, 0, 0, 0, 1)
        if (!(leverage < 1)) continue;
        const double residual = solver.solve(right)[5] * spacing;
        out_deviations.chart.push_back(slot_chart[k]);
        out_deviations.vertex.push_back(slot_vertex[k]);
        out_deviations.magnitude.push_back(std::abs(residual) / std::sqrt(1 - leverage));
    }
    return out_deviations;
}

// Under noise σ a vertex's deviation has a standard deviation of σ (median of its
// magnitude 0.674 σ), and a locally exact surface leaves an RMS of about 0.9 σ.
constexpr double kLeftByExactSurface = 0.9;
constexpr double kDeviationCalibration = kLeftByExactSurface / 0.674;
// Measured vertices a chart needs for a median of its own.
constexpr std::size_t kOwnMedian = 30;

// The most noise a plane fitted to k points leaves room for, when it leaves them a sum of
// squared distances `squares` over `freedom` = k − 3 degrees of freedom (for several
// planes, the sums of both): the upper 95 % confidence limit of σ, by the Wilson–Hilferty
// approximation of the χ² quantile (below the true one at few degrees of freedom: a looser
// limit), as the RMS an exact surface leaves; infinite without freedom. On a curved
// surface the plane leaves its bend too: the limit only errs high.
double plane_noise_limit(double squares, double freedom) {
    constexpr double kZ = 1.645;  // the standard normal's 95 % quantile
    const double root = freedom > 0 ? 1 - 2 / (9 * freedom) - kZ * std::sqrt(2 / (9 * freedom)) : 0;
    if (!(root > 0)) return std::numeric_limits<double>::infinity();
    return kLeftByExactSurface * std::sqrt(squares / (freedom * root * root * root));
}

// Per chart, the roughness of a chart too small for a median of its own (kOwnMedian): the
// whole mesh's median; in a connected component without as many measured vertices, no more
// than plane_noise_limit over its charts, each fitted by its own plane; and a chart of
// faces all `wide` against the noise (per face: no noise made that chart), no more than its
// own plane's limit. A slab beside a small noisy plate, apart from it, no vertex of its
// faces (a dozen triangles) with two rings in its own chart, took the plate's median, read
// across creases the noise garbles: 4.5 σ, within which one elliptic cylinder explained the
// whole slab; a coarse noisy countersunk plate's face and sides took the median of its
// countersink's chart, read beside bends, and were one ellipsoid. (Every small chart
// bounded by its own plane, even at 95 % confidence, put some of a fine noisy part's
// hundreds of noise charts below its noise, and Lloyd grew regions into them; so did each
// component's own median, on the noisy plate assembly's fine plates.)
std::vector<double> unmeasured_roughness(const Model& model, const VertexDeviations& deviations,
                                         const std::vector<int>& chart, int chart_count, const std::vector<char>& wide) {
    std::vector<int> component(chart_count, 0);
    for (int f = 0; f < model.face_count(); ++f) component[chart[f]] = model.component[f];
    std::vector<std::size_t> measured(model.component_count, 0), chart_measured(chart_count, 0);
    for (int c : deviations.chart) ++measured[component[c]], ++chart_measured[c];
    std::vector<char> wide_chart(chart_count, 1);
    for (int f = 0; f < model.face_count(); ++f) wide_chart[chart[f]] &= wide[f];
    std::vector<double> own(chart_count, std::numeric_limits<double>::infinity());
    // (chart, vertex), each once, of the charts whose planes bound their noise: those of
    // unmeasured components, and unmeasured charts of wide faces.
    std::vector<std::pair<int, int>> members;
    for (int f = 0; f < model.face_count(); ++f)
        if (measured[model.component[f]] < kOwnMedian || (wide_chart[chart[f]] && chart_measured[chart[f]] < kOwnMedian))
            for (int v : model.triangles[f]) members.emplace_back(chart[f], v);
    std::sort(members.begin(), members.end());
    members.erase(std::unique(members.begin(), members.end()), members.end());
    std::vector<double> squares(model.component_count, 0.0), freedom(model.component_count, 0.0);
    for (std::size_t begin = 0, end = 0; begin < members.size(); begin = end) {
        const int c = members[begin].first;
        Vec3 centre = Vec3::Zero();
        for (end = begin; end < members.size() && members[end].first == c; ++end) centre += model.points[members[end].second];
        const double k = static_cast<double>(end - begin);
        if (k < 4) continue;
        centre /= k;
        Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
        for (std::size_t i = begin; i < end; ++i) {
            const Vec3 d = model.points[members[i].second] - centre;
            scatter += d * d.transpose();
        }
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter, Eigen::EigenvaluesOnly);
        const double least = std::max(0.0, solver.eigenvalues()[0]);
        if (wide_chart[c]) own[c] = plane_noise_limit(least, k - 3);
        if (measured[component[c]] >= kOwnMedian) continue;
        squares[component[c]] += least;
        freedom[component[c]] += k - 3;
    }
    std::vector<double> part(model.component_count, std::numeric_limits<double>::infinity());
    for (int k = 0; k < model.component_count; ++k)
        if (measured[k] < kOwnMedian) part[k] = plane_noise_limit(squares[k], freedom[k]);
    const double overall = kDeviationCalibration * median(deviations.magnitude);
    std::vector<double> roughness(chart_count);
    for (int c = 0; c < chart_count; ++c) roughness[c] = std::min({overall, own[c], part[component[c]]});
    return roughness;
}

// Per chart: the median of its vertices' deviations (a bend inside a chart, a tangent edge
// between a cylinder and a chamfer, affects a line of vertices only), scaled so that
// under noise it is the RMS distance a locally exact surface leaves (samples at vertices
// and barycentres); a chart with fewer than 30 takes `unmeasured` (unmeasured_roughness).
// Where half a chart's vertices or more lie `beside_bend` (per vertex, or empty; a
// countersink two facets tall between two bends), the median is one of theirs: it is
// taken over the others. An `exact` chart (exact_groups) has no noise to measure: its
// vertices beside bends never count, and the others, however few, are its own (none: 0),
// not the whole mesh's (a coarse chamfered box, 44 triangles, all its vertices on
// chamfers, had a roughness of 8 % of its size and came out as one sphere).
std::vector<double> chart_roughness(const VertexDeviations& deviations, int chart_count,
                                    const std::vector<char>& beside_bend, const std::vector<char>& exact,
                                    const std::vector<double>& unmeasured) {
    std::vector<std::vector<double>> magnitudes(chart_count), away(chart_count);
    for (std::size_t i = 0; i < deviations.magnitude.size(); ++i) {
        magnitudes[deviations.chart[i]].push_back(deviations.magnitude[i]);
        if (!beside_bend.empty() && !beside_bend[deviations.vertex[i]]) away[deviations.chart[i]].push_back(deviations.magnitude[i]);
    }
    std::vector<double> roughness(chart_count);
    for (int c = 0; c < chart_count; ++c) {
        if (exact[c]) {
            roughness[c] = kDeviationCalibration * median(std::move(beside_bend.empty() ? magnitudes[c] : away[c]));
            continue;
        }
        if (2 * away[c].size() <= magnitudes[c].size() && away[c].size() >= kOwnMedian) magnitudes[c].swap(away[c]);
        roughness[c] = magnitudes[c].size() >= kOwnMedian ? kDeviationCalibration * median(std::move(magnitudes[c])) : unmeasured[c];
    }
    return roughness;
}

// Per group of faces (`group`: per face, 0 to count - 1), whether its tessellation is
// exact: half its faces or more lie in one plane with a neighbour of the group, to the
// stored precision, which no noise leaves (a coarse CAD export's faces are two triangles
// or a fan each). In such a chart, a vertex's deviation from a quadric through its two
// rings measures the part's own edges and corners (a chamfer a triangle wide), not noise.
std::vector<char> exact_groups(const Model& model, const std::vector<int>& group, int count) {
    const DualGraph& g = model.graph;
    std::vector<int> faces(count, 0), coplanar(count, 0);
    for (int f = 0; f < model.face_count(); ++f) {
        const int c = group[f];
        ++faces[c];
        for (int e = g.begin(f); e < g.end(f); ++e)
            if (group[g.neighbor[e]] == c && exactly_coplanar(model, f, g.neighbor[e])) {
                ++coplanar[c];
                break;
            }
    }
    std::vector<char> exact(count);
    for (int c = 0; c < count; ++c) exact[c] = faces[c] > 0 && 2 * coplanar[c] >= faces[c];
    return exact;
}

// The angle between the normals of face a and its neighbour across dual-graph link `link`.
double turn(const DualGraph& g, const std::vector<Vec3>& normal, int a, int link) {
    return std::acos(std::clamp(normal[a].dot(normal[g.neighbor[link]]), -1.0, 1.0));
}

// Whether the bend across dual edge e is a chord of a polygonal arc rather than a lone edge
// such as a chamfer's: on each side, within two faces not across another bend, the arc
// bends again by a similar angle (half to twice as much: a coarse hole's facets are
// irregular), the same way, along a parallel edge beside it (the next facet column). A
// chamfer of one row has its other bend on one side only: the face beyond it is flat.
bool polygonal_arc_chord(const Model& model, const std::vector<Vec3>& raw, int f, int e, double crease_limit) {
    const DualGraph& g = model.graph;
    struct Bend {
        Vec3 from, direction, middle;  // the shared edge: an end, its unit direction, its middle
        double angle, length;
        int way;  // convex or concave: the same seen from either side
    };
    auto bend_of = [&](int a, int link) {
        const int b = g.neighbor[link];
        const std::array<int, 2> shared = shared_edge(model, a, b);
        Bend out{};
        if (shared[0] < 0) return out;
        const Vec3 &p = model.points[shared[0]], &q = model.points[shared[1]];
        out.from = p, out.length = (q - p).norm(), out.direction = (q - p) / std::max(out.length, 1e-300);
        out.middle = 0.5 * (p + q), out.angle = turn(g, raw, a, link);
        out.way = (raw[b] - raw[a]).dot(model.barycentres[b] - model.barycentres[a]) >= 0 ? 1 : -1;
        return out;
    };
    const Bend self = bend_of(f, e);
    if (!(self.length > 0)) return false;
    const int h = g.neighbor[e];
    auto bends_again = [&](int start, int excluded) {
        // Faces within two links of `start` that bend by less than half as much, not
        // through `excluded`.
        std::vector<int> reached{start}, frontier{start};
        for (int depth = 0; depth < 2; ++depth) {
            std::vector<int> next;
            for (int a : frontier)
                for (int l = g.begin(a); l < g.end(a); ++l) {
                    const int b = g.neighbor[l];
                    if (b == excluded || turn(g, raw, a, l) >= 0.5 * self.angle ||
                        std::find(reached.begin(), reached.end(), b) != reached.end())
                        continue;
                    reached.push_back(b), next.push_back(b);
                }
            frontier.swap(next);
        }
        for (int a : reached)
            for (int l = g.begin(a); l < g.end(a); ++l) {
                if (g.neighbor[l] == excluded) continue;
                const double angle = turn(g, raw, a, l);
                if (angle < 0.5 * self.angle || angle > crease_limit) continue;
                const Bend other = bend_of(a, l);
                if (!(other.length > 0) || std::abs(other.direction.dot(self.direction)) < 0.9) continue;
                const Vec3 off = other.middle - self.from;
                // The same bend line continued is no second bend; nor is one of another size
                // or turning the other way.
                if ((off - off.dot(self.direction) * self.direction).norm() < 0.1 * self.length) continue;
                if (other.angle > 2 * self.angle || other.way != self.way) continue;
                return true;
            }
        return false;
    };
    return bends_again(f, h) && bends_again(h, f);
}

}  // namespace

Features detect_features(const Model& model, const FeatureOptions& options) {
    const DualGraph& g = model.graph;
    const int n = model.face_count();
    Features out;
    const std::vector<Vec3> raw = face_normals(model);

    // Noise turns the normals of faces not much larger than it at random: such faces
    // make no creases, and their normals are filtered harder.
    const NoiseLevels levels = noise_levels(model, raw, options.crease_angle);
    double noise = levels.smooth;
    std::vector<double> altitude(n);
    for (int f = 0; f < n; ++f) altitude[f] = narrowest_width(model, f);
    // Noise of the faces' own width (a finely meshed scan) turns every face at random, by
    // more than the filter's range, and no vertex is smooth: the smooth vertices' noise
    // reads low or nothing, and the filter, which weighs neighbours by how close their
    // normals are, weighs none. Where most neighbouring faces differ by more than the
    // filter's range and fewer than a tenth of the faces lie in one plane with a neighbour
    // (such noise leaves none so; a coarse or decimated export's holes and fans bend as
    // much), the noise is that of all vertices, and each face starts from the mean normal
    // of its most consistent patch, wide enough that the differences between such means
    // stay well inside the range.
    std::vector<double> link_angle;
    for (int f = 0; f < n; ++f)
        for (int e = g.begin(f); e < g.end(f); ++e)
            if (f < g.neighbor[e]) link_angle.push_back(turn(g, raw, f, e));
    int rings = 0;
    // Per face: in one plane with a neighbour to the stored precision (no noise leaves it).
    std::vector<char> flat(n, 0);
    int flat_faces = 0;
    double flat_area = 0;
    for (int f = 0; f < n; ++f) {
        flat[f] = coplanar_with_a_neighbour(model, f);
        flat_faces += flat[f];
        if (flat[f]) flat_area += model.areas[f];
    }
    // By area too: an export meshes its curved detail as finely as its tolerance asks and a
    // plane with the fewest triangles its outline allows (Voron's z belt clip: 39 % of its
    // faces, 87 % of its area). Counted by faces alone it was no exact tessellation, its
    // charts' noise read where its teeth and chamfers meet its planes, 1.8e-3 of its size.
    out.exact = n > 0 && (2 * flat_faces >= n || 2 * flat_area >= model.total_area);
    if (median(std::move(link_angle)) > options.filter_range && 10 * flat_faces < n) {
        noise = std::max(noise, levels.all);
        // k faces' mean tilts by 2σ/(h√k); a patch of r rings holds about 1 + 1.5 r(r + 1).
        const double ratio = 2 * noise / (0.5 * options.filter_range * median(altitude));
        for (rings = 1; rings < 6 && 1 + 1.5 * rings * (rings + 1) < ratio * ratio; ++rings) {}
    }
    std::vector<int> averaged(n, 1);  // faces each face's starting normal averages
    std::vector<Vec3> start = rings > 0 ? guidance_normals(g, raw, model.areas, rings, averaged) : raw;
    // Wide faces, which the noise tilts by half the range or less on their own, keep their
    // own normals: the median face's patches took a slab beside a small noisy part whole,
    // its sides and far face too, one normal. (Fewer rings for faces between, as their width
    // would have it, left the noisy pipe junction's larger faces noisier than that says:
    // 344 charts.) Nor can noise make a chart of them (unmeasured_roughness).
    std::vector<char> wide(n);
    for (int f = 0; f < n; ++f) wide[f] = 2 * noise <= 0.5 * options.filter_range * altitude[f];
    // Nor do faces whose patch lies across a crease from them (own_normals).
    if (rings > 0) {
        const std::vector<char> own = own_normals(g, raw, start, wide, altitude, noise, options.crease_angle);
        for (int f = 0; f < n; ++f)
            if (own[f]) start[f] = raw[f], averaged[f] = 1;
    }
    std::vector<char> reliable(n);
    std::vector<double> range(n);  // the filter's normal difference of half weight, per face
    for (int f = 0; f < n; ++f) {
        // Noise σ tilts a face of altitude h by about 2σ/h, the mean of k such faces by
        // 2σ/(h√k): differences that large are noise.
        const double width = altitude[f] * std::sqrt(static_cast<double>(averaged[f]));
        reliable[f] = width > 3 * noise;
        range[f] = std::clamp(2 * noise / std::max(width, 1e-300), options.filter_range, 0.6);
    }
    out.normals = filter_normals(g, start, range, options.filter_iterations);
    out.crease = find_creases(g, out.normals, options.crease_angle);
    find_charts(g, reliable, out.exact, out);
    const VertexDeviations deviations = vertex_deviations(model, out.normals, out);
    const std::vector<char> exact = exact_groups(model, out.chart, out.chart_count);
    const std::vector<double> unmeasured = unmeasured_roughness(model, deviations, out.chart, out.chart_count, wide);
    auto roughness_beside = [&](const std::vector<char>& beside_bend) {
        return chart_roughness(deviations, out.chart_count, beside_bend, exact, unmeasured);
    };
    std::vector<double> per_chart = roughness_beside({});

    // Edges bent by more than half the crease angle are no chords of a smooth surface (a
    // chamfer's, a countersink's), unless they are chords of a polygonal arc well beyond
    // what the chart's noise does to a face's normal (about 2σ/width): noise puts bends
    // beside bends anywhere. Per link.
    const double smooth_limit = 0.5 * options.crease_angle * M_PI / 180, crease_limit = options.crease_angle * M_PI / 180;
    std::vector<double> width(n);
    for (int f = 0; f < n; ++f) width[f] = narrowest_width(model, f);  // a sliver's length is no chord
    std::vector<double> angle(g.neighbor.size(), 0.0);
    std::vector<char> chord(g.neighbor.size(), 0), candidate(g.neighbor.size(), 0), arc_like(g.neighbor.size(), 0);
    for (int f = 0; f < n; ++f)
        for (int e = g.begin(f); e < g.end(f); ++e) {
            if (out.crease[e] || !(g.edge_length[e] > 0)) continue;
            angle[e] = turn(g, raw, f, e);
            if (angle[e] <= smooth_limit) {
                chord[e] = arc_like[e] = 1;
                continue;
            }
            const bool arc = polygonal_arc_chord(model, raw, f, e, crease_limit);
            chord[e] = angle[e] >= 8 * per_chart[out.chart[f]] / width[f] && arc;
            arc_like[e] = arc;
            candidate[e] = !arc;
        }
    // A chart's roughness is no measure of its noise where more than half its vertices lie
    // beside bends (a countersink two facets tall between the bore and the face): measured
    // away from the edges that may be bends, it tells which are (beyond what the noise does
    // to the normal of the narrower face: a sliver's normal is no evidence of a bend), and
    // then away from those.
    auto beside = [&](const std::vector<char>& links) {
        std::vector<char> on(model.points.size(), 0), near;
        bool any = false;
        for (int f = 0; f < n; ++f)
            for (int e = g.begin(f); e < g.end(f); ++e)
                if (links[e]) {
                    any = true;
                    for (int v : shared_edge(model, f, g.neighbor[e]))
                        if (v >= 0) on[v] = 1;
                }
        if (!any) return near;
        // A vertex's fit reaches two rings beyond it.
        for (int grown = 0; grown < 2; ++grown) {
            near = on;
            for (int f = 0; f < n; ++f) {
                const Triangle& t = model.triangles[f];
                if (on[t[0]] || on[t[1]] || on[t[2]]) near[t[0]] = near[t[1]] = near[t[2]] = 1;
            }
            on.swap(near);
        }
        return on;
    };
    const std::vector<char> beside_candidates = beside(candidate);
    if (!beside_candidates.empty()) {
        const std::vector<double> away = roughness_beside(beside_candidates);
        std::vector<char> bend(g.neighbor.size(), 0);
        for (int f = 0; f < n; ++f)
            for (int e = g.begin(f); e < g.end(f); ++e)
                bend[e] = candidate[e] && angle[e] >= 8 * away[out.chart[f]] / std::min(width[f], width[g.neighbor[e]]);
        const std::vector<char> beside_bends = beside(bend);
        if (!beside_bends.empty()) per_chart = roughness_beside(beside_bends);
    }

    // A clean tessellation has roughness too: its flat facets stand off the smooth
    // surface by the sagitta of the arc across them, about altitude × dihedral / 8 over
    // the chords (the largest of a face's); a fit leaves an RMS of up to as much, the
    // vertices lying on the surface. Per face: a curved face beside a flat one in a chart
    // (a fillet) keeps its own. A flat face (in one plane with a neighbour, as no noise
    // leaves it) over four times as wide as the facet across its bend is no chord of that
    // arc, whose facets differ little in width: it gets the facet's sag. A sheet's face of
    // two long triangles beside a rolled edge of 7° facets took the sag of a 7° turn over
    // its own width, which explained a region of the face and half the roll.
    constexpr double kSagittaRms = 1.0;
    // On an exact tessellation no noise moved a vertex, so what a chart's deviations read
    // beyond its facets' sag is where its surfaces meet (a fillet, a chamfer or a
    // countersink below the crease angle), not noise: the chart's noise is no more than the
    // largest sag of its smooth bends and arc chords, noise or not. A circlip exported with
    // filleted edges read 0.6 % of its size so, and its automatic run stopped "fitted" at 8
    // regions, one plane over a face and its fillets (RMS 4.5e-3 of the diagonal; now 28
    // regions, 3.5e-4).
    std::vector<double> sagitta(n, 0.0), chart_sagitta(out.chart_count, 0.0);
    for (int f = 0; f < n; ++f)
        for (int e = g.begin(f); e < g.end(f); ++e) {
            if (!arc_like[e]) continue;
            const double w = flat[f] && width[f] > 4 * width[g.neighbor[e]] ? width[g.neighbor[e]] : width[f];
            const double sag = w * angle[e] / 8;
            if (chord[e]) sagitta[f] = std::max(sagitta[f], sag);
            chart_sagitta[out.chart[f]] = std::max(chart_sagitta[out.chart[f]], kSagittaRms * sag);
        }
    if (out.exact)
        for (int c = 0; c < out.chart_count; ++c) per_chart[c] = std::min(per_chart[c], chart_sagitta[c]);
    out.roughness.resize(n);
    out.arc_facet.resize(n);
    for (int f = 0; f < n; ++f) {
        out.arc_facet[f] = sagitta[f] > kStoredPrecision;
        out.roughness[f] = std::hypot(per_chart[out.chart[f]], kSagittaRms * sagitta[f]);
    }
    return out;
}

}  // namespace vqsa
