#include "post/seams.h"

#include "fitting/face_errors.h"
#include "fitting/least_squares.h"

#include <algorithm>
#include <set>

namespace vqsa {

namespace {

struct Region {
    std::vector<int> faces;
    double error = 0;  // Σ d(t, P) under its chosen surface
};

}  // namespace

int simplify_seams(const Model& model, std::vector<int>& labels, std::vector<Proxy>& proxies,
                   std::vector<ModelChoice>& choices, const std::vector<char>* crease, const SeamOptions& options) {
    const int count = static_cast<int>(proxies.size());
    const DualGraph& g = model.graph;
    auto link_open = [&](int e) { return !crease || !(*crease)[e]; };
    FaceErrors evaluator;
    evaluator.reset(model, quadrics_of(proxies));
    std::vector<Region> regions(count);
    for (int f = 0; f < model.face_count(); ++f) {
        regions[labels[f]].faces.push_back(f);
        regions[labels[f]].error += evaluator(f, labels[f]);
    }
    const int plane_parameters = degrees_of_freedom(QuadricType::plane);
    std::vector<char> in_strip(model.face_count(), 0);
    int moved = 0;
    auto faces_without = [&](int r, const std::vector<int>& strip) {
        for (int f : strip) in_strip[f] = 1;
        std::vector<int> rest;
        for (int f : regions[r].faces)
            if (!in_strip[f]) rest.push_back(f);
        for (int f : strip) in_strip[f] = 0;
        return rest;
    };
    // A first look at a region without a strip, on a few hundred of its vertices: most
    // seams of a free-form surface change no type, and this tells them cheaply.
    auto select_without = [&](int r, const std::vector<int>& strip) {
        const std::vector<int> rest = faces_without(r, strip);
        return select_model(thinned(vertex_samples(model.points, model.triangles, rest), options.screening_samples),
                            fit_region(moments_of(model, rest), options.fit).quadric, options.selection);
    };
    for (int a = 0; a < count; ++a) {
        if (choices[a].chosen.parameters <= plane_parameters) continue;
        std::set<int> neighbours;
        for (int f : regions[a].faces)
            for (int e = g.begin(f); e < g.end(f); ++e)
                if (labels[g.neighbor[e]] != a && link_open(e)) neighbours.insert(labels[g.neighbor[e]]);
        for (int b : neighbours) {
            if (!(proxies[b].area > 0)) continue;
            const double mse = regions[b].error / proxies[b].area;
            auto explained = [&](int f) { return evaluator(f, b) <= options.tolerance * mse * model.areas[f]; };
            // The faces of a reached from b across open edges, flooding while b explains them,
            // up to `rings` faces deep.
            std::vector<int> strip, depth;
            double strip_area = 0;
            bool too_large = false;
            for (int f : regions[a].faces)
                for (int e = g.begin(f); e < g.end(f); ++e)
                    if (labels[g.neighbor[e]] == b && link_open(e) && !in_strip[f] && explained(f)) {
                        in_strip[f] = 1, strip.push_back(f), depth.push_back(1);
                        break;
                    }
            for (std::size_t k = 0; k < strip.size() && !too_large; ++k) {
                strip_area += model.areas[strip[k]];
                too_large = strip_area > options.max_fraction * proxies[a].area;
                for (int e = g.begin(strip[k]); e < g.end(strip[k]); ++e) {
                    const int h = g.neighbor[e];
                    if (labels[h] != a || in_strip[h] || !link_open(e) || !explained(h)) continue;
                    if (depth[k] == options.rings) continue;
                    in_strip[h] = 1, strip.push_back(h), depth.push_back(depth[k] + 1);
                }
            }
            for (int f : strip) in_strip[f] = 0;
            if (strip.empty() || too_large) continue;
            // Of those, the faces b explains better than a's surface without them does: a
            // band of a's own faces near the seam, within b's error, stays.
            const ModelChoice without = select_without(a, strip);
            if (without.chosen.parameters >= choices[a].chosen.parameters) continue;
            FaceErrors rival;
            rival.reset(model, {without.chosen.quadric});
            std::vector<int> kept_strip;
            for (int f : strip)
                if (evaluator(f, b) < rival(f, 0)) kept_strip.push_back(f);
            if (kept_strip.empty()) continue;
            strip = std::move(kept_strip);
            std::vector<int> rest = faces_without(a, strip);
            if (rest.size() < 3) continue;
            const Moments rest_moments = moments_of(model, rest);
            const ModelChoice simpler =
                select_model(vertex_samples(model.points, model.triangles, rest), fit_region(rest_moments, options.fit).quadric, options.selection);
            if (simpler.chosen.parameters >= choices[a].chosen.parameters) continue;
            std::vector<int> grown = regions[b].faces;
            grown.insert(grown.end(), strip.begin(), strip.end());
            Moments grown_moments = proxies[b].moments;
            for (int f : strip) add_to(grown_moments, model.moments[f]);
            const ModelChoice kept =
                select_model(vertex_samples(model.points, model.triangles, grown), fit_region(grown_moments, options.fit).quadric, options.selection);
            if (kept.chosen.type != choices[b].chosen.type) continue;

            for (int f : strip) labels[f] = b;
            auto commit = [&](int r, std::vector<int> faces, const Moments& m, const ModelChoice& choice) {
                Proxy& p = proxies[r];
                p.moments = m;
                p.area = m[0];
                p.faces = static_cast<int>(faces.size());
                p.quadric = choice.chosen.quadric;
                choices[r] = choice;
                regions[r].faces = std::move(faces);
            };
            commit(a, std::move(rest), rest_moments, simpler);
            commit(b, std::move(grown), grown_moments, kept);
            evaluator.reset(model, quadrics_of(proxies));
            for (int r : {a, b}) {
                regions[r].error = 0;
                for (int f : regions[r].faces) regions[r].error += evaluator(f, r);
            }
            moved += static_cast<int>(strip.size());
            // a changed: its other seams are judged anew, if it is still not a plane.
            if (choices[a].chosen.parameters <= plane_parameters) break;
        }
    }
    return moved;
}

}  // namespace vqsa
