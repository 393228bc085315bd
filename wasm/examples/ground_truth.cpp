#include "ground_truth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace vqsa {

std::vector<int> best_assignment(const std::vector<std::vector<double>>& weight) {
    const int rows = static_cast<int>(weight.size());
    const int cols = rows ? static_cast<int>(weight[0].size()) : 0;
    const int n = std::max(rows, cols);
    auto cost = [&](int i, int j) { return i < rows && j < cols ? -weight[i][j] : 0.0; };
    // Potentials u (rows), v (columns); p[j]: row matched to column j (1-based, 0 = none).
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> u(n + 1, 0), v(n + 1, 0);
    std::vector<int> p(n + 1, 0), way(n + 1, 0);
    for (int i = 1; i <= n; ++i) {
        p[0] = i;
        int j0 = 0;
        std::vector<double> least(n + 1, inf);
        std::vector<char> used(n + 1, 0);
        do {
            used[j0] = 1;
            const int i0 = p[j0];
            double delta = inf;
            int j1 = 0;
            for (int j = 1; j <= n; ++j) {
                if (used[j]) continue;
                const double c = cost(i0 - 1, j - 1) - u[i0] - v[j];
                if (c < least[j]) least[j] = c, way[j] = j0;
                if (least[j] < delta) delta = least[j], j1 = j;
            }
            for (int j = 0; j <= n; ++j) {
                if (used[j]) u[p[j]] += delta, v[j] -= delta;
                else least[j] -= delta;
            }
            j0 = j1;
        } while (p[j0] != 0);
        do {
            const int j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
        } while (j0);
    }
    std::vector<int> assignment(rows, -1);
    for (int j = 1; j <= n; ++j)
        if (p[j] >= 1 && p[j] <= rows && j <= cols) assignment[p[j] - 1] = j - 1;
    return assignment;
}

ParameterError parameter_error(const TrueSurface& truth, const Classification& found) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    constexpr double degrees = 180 / 3.14159265358979323846;
    ParameterError e{nan, nan, nan};
    const QuadricType t = truth.type;
    if (t == QuadricType::plane || t == QuadricType::cylinder || t == QuadricType::cone)
        e.axis_degrees = std::acos(std::min(1.0, std::abs(truth.axis.normalized().dot(found.axis().normalized())))) * degrees;
    if (t == QuadricType::sphere || t == QuadricType::cylinder) e.radius_relative = std::abs(found.radius - truth.radius) / truth.radius;
    if (t == QuadricType::cone) e.half_angle_degrees = std::abs(found.half_angle - truth.half_angle) * degrees;
    return e;
}

Samples true_face_vertices(const Part& part, int face) {
    std::vector<int> faces;
    for (std::size_t t = 0; t < part.face.size(); ++t)
        if (part.face[t] == face) faces.push_back(static_cast<int>(t));
    return vertex_samples(part.mesh.vertices, part.mesh.triangles, faces);
}

std::vector<CorpusCase> cad_corpus(const std::vector<std::string>& parts) {
    std::vector<CorpusCase> cases;
    const std::vector<std::string> all = part_names();
    for (const std::string& part : parts) {
        const auto index = std::find(all.begin(), all.end(), part) - all.begin();
        if (index == static_cast<long>(all.size())) throw std::invalid_argument("unknown part '" + part + "'");
        std::uint64_t seed = 1 + 3 * static_cast<std::uint64_t>(index);
        for (const std::string variant : {"clean", "noisy", "irregular"}) {
            PartOptions o;
            o.random_pose = true;
            o.seed = seed++;
            o.noise = variant == "noisy" ? 0.002 : 0;
            o.irregular = variant == "irregular";
            cases.push_back({part, variant, o});
        }
    }
    return cases;
}

PartitionScore score_partition(const Part& part, const std::vector<int>& labels, int regions) {
    const int faces = static_cast<int>(part.surfaces.size());
    std::vector<std::vector<double>> overlap(regions, std::vector<double>(faces, 0.0));
    double total = 0;
    for (std::size_t t = 0; t < labels.size(); ++t) {
        const Triangle& tri = part.mesh.triangles[t];
        const Vec3 &a = part.mesh.vertices[tri[0]], &b = part.mesh.vertices[tri[1]], &c = part.mesh.vertices[tri[2]];
        const double area = 0.5 * (b - a).cross(c - a).norm();
        total += area;
        if (labels[t] >= 0) overlap[labels[t]][part.face[t]] += area;
    }
    PartitionScore score;
    score.face_of = best_assignment(overlap);
    double matched = 0;
    std::vector<double> region_area(regions, 0), face_area(faces, 0);
    for (int r = 0; r < regions; ++r)
        for (int f = 0; f < faces; ++f) region_area[r] += overlap[r][f], face_area[f] += overlap[r][f];
    score.clean_match.assign(regions, 0);
    for (int r = 0; r < regions; ++r) {
        const int f = score.face_of[r];
        if (f < 0) continue;
        matched += overlap[r][f];
        score.clean_match[r] = overlap[r][f] >= 0.9 * region_area[r] && overlap[r][f] >= 0.9 * face_area[f];
    }
    score.accuracy = total > 0 ? matched / total : 0;
    return score;
}

int two_part_regions(const Mesh& mesh, const Result& result) {
    int count = 0;
    for (const ProxyResult& p : result.proxies) {
        if (!has_two_parts(p.shape)) continue;
        PartWeights parts;  // by area
        double total = 0;
        for (std::size_t t = 0; t < result.face_labels.size(); ++t) {
            if (result.face_labels[t] != p.id) continue;
            const Triangle& tri = mesh.triangles[t];
            const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
            const double area = 0.5 * (b - a).cross(c - a).norm();
            total += area;
            const int side = part_of(p.shape, (a + b + c) / 3, 2 * p.type_rms);
            if (side != 0) parts.weight[side > 0 ? 0 : 1] += area, ++parts.count[side > 0 ? 0 : 1];
        }
        count += parts.both(total, 0.01);
    }
    return count;
}

double area_within_one_chart(const Model& model, const std::vector<int>& chart, const std::vector<int>& labels,
                             int regions) {
    std::vector<std::map<int, double>> area(regions);
    for (int f = 0; f < model.face_count(); ++f) area[labels[f]][chart[f]] += model.areas[f];
    double within = 0;
    for (const auto& by_chart : area) {
        double largest = 0;
        for (const auto& [c, a] : by_chart) largest = std::max(largest, a);
        within += largest;
    }
    return model.total_area > 0 ? within / model.total_area : 1;
}

}  // namespace vqsa
