#include "post/seams.h"

#include "fitting/face_errors.h"
#include "fitting/least_squares.h"

#include <algorithm>
#include <set>

namespace vqsa {

struct SeamSimplifier::Region {
    std::vector<int> faces;
    double error = 0;  // Σ d(t, P) under its chosen surface
};

SeamSimplifier::SeamSimplifier(const Model& model, std::vector<int>& labels, std::vector<Proxy>& proxies,
                               std::vector<ModelChoice>& choices, const std::vector<char>* crease,
                               const SeamOptions& options, const std::vector<char>* may_change)
    : model_(model), labels_(labels), proxies_(proxies), choices_(choices), crease_(crease), may_change_(may_change),
      options_(options),
      regions_(proxies.size()), in_strip_(model.face_count(), 0), vertex_kept_(model.points.size(), 0) {
    evaluator_.reset(model, quadrics_of(proxies));
    for (int f = 0; f < model.face_count(); ++f) {
        regions_[labels[f]].faces.push_back(f);
        regions_[labels[f]].error += evaluator_(f, labels[f]);
    }
}

SeamSimplifier::~SeamSimplifier() = default;

bool SeamSimplifier::step() {
    if (next_ >= static_cast<int>(regions_.size())) return false;
    simplify(next_++);
    return next_ < static_cast<int>(regions_.size());
}

double SeamSimplifier::fraction() const { return regions_.empty() ? 1 : double(next_) / regions_.size(); }

void SeamSimplifier::simplify(int a) {
    const DualGraph& g = model_.graph;
    auto link_open = [&](int e) { return !crease_ || !(*crease_)[e]; };
    const int plane_parameters = degrees_of_freedom(QuadricType::plane);
    auto faces_without = [&](int r, const std::vector<int>& strip) {
        for (int f : strip) in_strip_[f] = 1;
        std::vector<int> rest;
        for (int f : regions_[r].faces)
            if (!in_strip_[f]) rest.push_back(f);
        for (int f : strip) in_strip_[f] = 0;
        return rest;
    };
    // A first look at a region without a strip (`rest`), on a few hundred of its vertices:
    // most seams of a free-form surface change no type, and this tells them cheaply.
    auto screen = [&](const std::vector<int>& rest) {
        return select_model(thinned(region_samples(model_, rest), options_.screening_samples),
                            fit_region(moments_of(model_, rest), options_.fit).quadric, options_.selection);
    };
    // Whether every vertex of the strip is also one of `rest`.
    auto keeps_every_vertex = [&](const std::vector<int>& rest, const std::vector<int>& strip) {
        for (int f : rest)
            for (int v : model_.triangles[f]) vertex_kept_[v] = 1;
        bool all = true;
        for (int f : strip)
            for (int v : model_.triangles[f]) all = all && vertex_kept_[v];
        for (int f : rest)
            for (int v : model_.triangles[f]) vertex_kept_[v] = 0;
        return all;
    };
    auto may_change = [&](int r) { return !may_change_ || (*may_change_)[r]; };
    if (choices_[a].chosen.parameters <= plane_parameters || !may_change(a)) return;
    std::set<int> neighbours;
    for (int f : regions_[a].faces)
        for (int e = g.begin(f); e < g.end(f); ++e)
            if (labels_[g.neighbor[e]] != a && link_open(e) && may_change(labels_[g.neighbor[e]]))
                neighbours.insert(labels_[g.neighbor[e]]);
    for (int b : neighbours) {
        if (!(proxies_[b].area > 0)) continue;
        const double mse = regions_[b].error / proxies_[b].area;
        auto explained = [&](int f) { return evaluator_(f, b) <= options_.tolerance * mse * model_.areas[f]; };
        // The faces of a reached from b across open edges, flooding while b explains them,
        // up to `rings` faces deep.
        std::vector<int> strip, depth;
        double strip_area = 0;
        bool too_large = false;
        for (int f : regions_[a].faces)
            for (int e = g.begin(f); e < g.end(f); ++e)
                if (labels_[g.neighbor[e]] == b && link_open(e) && !in_strip_[f] && explained(f)) {
                    in_strip_[f] = 1, strip.push_back(f), depth.push_back(1);
                    break;
                }
        for (std::size_t k = 0; k < strip.size() && !too_large; ++k) {
            strip_area += model_.areas[strip[k]];
            too_large = strip_area > options_.max_fraction * proxies_[a].area;
            for (int e = g.begin(strip[k]); e < g.end(strip[k]); ++e) {
                const int h = g.neighbor[e];
                if (labels_[h] != a || in_strip_[h] || !link_open(e) || !explained(h)) continue;
                if (depth[k] == options_.rings) continue;
                in_strip_[h] = 1, strip.push_back(h), depth.push_back(depth[k] + 1);
            }
        }
        for (int f : strip) in_strip_[f] = 0;
        if (strip.empty() || too_large) continue;
        // A strip that takes none of a's vertices leaves the vertices its selection judges
        // as they are: no simpler type (on coarse meshes, most one-face-deep strips).
        const std::vector<int> without_strip = faces_without(a, strip);
        if (keeps_every_vertex(without_strip, strip)) continue;
        // Of those, the faces b explains better than a's surface without them does: a
        // band of a's own faces near the seam, within b's error, stays.
        const ModelChoice without = screen(without_strip);
        if (without.chosen.parameters >= choices_[a].chosen.parameters) continue;
        FaceErrors rival;
        rival.reset(model_, {without.chosen.quadric});
        std::vector<int> kept_strip;
        for (int f : strip)
            if (evaluator_(f, b) < rival(f, 0)) kept_strip.push_back(f);
        if (kept_strip.empty()) continue;
        strip = std::move(kept_strip);
        std::vector<int> rest = faces_without(a, strip);
        if (rest.size() < 3) continue;
        const Moments rest_moments = moments_of(model_, rest);
        const ModelChoice simpler =
            select_model(region_samples(model_, rest), fit_region(rest_moments, options_.fit).quadric, options_.selection);
        if (simpler.chosen.parameters >= choices_[a].chosen.parameters) continue;
        std::vector<int> grown = regions_[b].faces;
        grown.insert(grown.end(), strip.begin(), strip.end());
        Moments grown_moments = proxies_[b].moments;
        for (int f : strip) add_to(grown_moments, model_.moments[f]);
        const ModelChoice kept =
            select_model(region_samples(model_, grown), fit_region(grown_moments, options_.fit).quadric, options_.selection);
        if (kept.chosen.type != choices_[b].chosen.type) continue;

        for (int f : strip) labels_[f] = b;
        auto commit = [&](int r, std::vector<int> faces, const Moments& m, const ModelChoice& choice) {
            Proxy& p = proxies_[r];
            p.moments = m;
            p.area = m[0];
            p.faces = static_cast<int>(faces.size());
            p.quadric = choice.chosen.quadric;
            choices_[r] = choice;
            regions_[r].faces = std::move(faces);
        };
        commit(a, std::move(rest), rest_moments, simpler);
        commit(b, std::move(grown), grown_moments, kept);
        evaluator_.reset(model_, quadrics_of(proxies_));
        for (int r : {a, b}) {
            regions_[r].error = 0;
            for (int f : regions_[r].faces) regions_[r].error += evaluator_(f, r);
        }
        // a changed: its other seams are judged anew, if it is still not a plane.
        if (choices_[a].chosen.parameters <= plane_parameters) break;
    }
}

}  // namespace vqsa
