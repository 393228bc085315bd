#include "post/graph_cut.h"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>

#include <algorithm>
#include <map>

namespace vqsa {

namespace {

using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
using FlowGraph = boost::adjacency_list<
    boost::vecS, boost::vecS, boost::directedS,
    boost::property<boost::vertex_color_t, boost::default_color_type,
                    boost::property<boost::vertex_distance_t, long,
                                    boost::property<boost::vertex_predecessor_t, Traits::edge_descriptor>>>,
    boost::property<boost::edge_capacity_t, double,
                    boost::property<boost::edge_residual_capacity_t, double,
                                    boost::property<boost::edge_reverse_t, Traits::edge_descriptor>>>>;

void add_arc(FlowGraph& g, int from, int to, double capacity, double reverse_capacity) {
    auto capacity_map = boost::get(boost::edge_capacity, g);
    auto reverse_map = boost::get(boost::edge_reverse, g);
    const auto forward = boost::add_edge(from, to, g).first;
    const auto backward = boost::add_edge(to, from, g).first;
    capacity_map[forward] = capacity;
    capacity_map[backward] = reverse_capacity;
    reverse_map[forward] = backward;
    reverse_map[backward] = forward;
}

}  // namespace

BoundarySmoother::BoundarySmoother(const Model& model, std::vector<Quadric> proxies, std::vector<int>& labels,
                                   const std::vector<int>& anchors, const SmoothingOptions& options,
                                   const std::vector<char>* crease, const std::vector<char>* regions)
    : model_(model), labels_(labels), options_(options), crease_(crease) {
    double total = 0;
    for (double l : model.graph.edge_length) total += l;
    mean_edge_length_ = model.graph.edge_length.empty() ? 1.0 : total / model.graph.edge_length.size();
    errors_.reset(model, std::move(proxies));
    pairs_ = adjacent_regions(model, labels);
    if (regions)
        pairs_.erase(std::remove_if(pairs_.begin(), pairs_.end(),
                                    [&](const auto& p) { return !(*regions)[p.first] || !(*regions)[p.second]; }),
                     pairs_.end());
    ring_.assign(model.face_count(), 0);
    node_.assign(model.face_count(), -1);
    anchored_.assign(model.face_count(), 0);
    for (int f : anchors)
        if (f >= 0) anchored_[f] = 1;
}

bool BoundarySmoother::step() {
    if (next_ >= static_cast<int>(pairs_.size())) return false;
    smooth(pairs_[next_].first, pairs_[next_].second);
    if (++next_ == static_cast<int>(pairs_.size())) reconnect();
    return true;
}

void BoundarySmoother::smooth(int a, int b) {
    const DualGraph& g = model_.graph;
    auto in_pair = [&](int f) { return labels_[f] == a || labels_[f] == b; };
    auto other = [&](int label) { return label == a ? b : a; };

    // The band: faces of a or b within `rings` hops of their common boundary.
    std::vector<int> band;
    for (int f = 0; f < model_.face_count(); ++f) {
        if (!in_pair(f)) continue;
        for (int e = g.begin(f); e < g.end(f); ++e)
            if (labels_[g.neighbor[e]] == other(labels_[f])) {
                ring_[f] = 1;
                band.push_back(f);
                break;
            }
    }
    if (band.empty()) return;
    for (std::size_t i = 0; i < band.size(); ++i) {
        const int f = band[i];
        if (ring_[f] >= options_.rings) continue;
        for (int e = g.begin(f); e < g.end(f); ++e) {
            const int n = g.neighbor[e];
            if (in_pair(n) && ring_[n] == 0) ring_[n] = ring_[f] + 1, band.push_back(n);
        }
    }

    // Nodes: the band, plus the faces just outside it (hard constraints V0, V1).
    std::vector<int> faces = band;
    for (int f : band)
        for (int e = g.begin(f); e < g.end(f); ++e) {
            const int n = g.neighbor[e];
            if (in_pair(n) && ring_[n] == 0 && node_[n] < 0) {
                node_[n] = -2;  // queued
                faces.push_back(n);
            }
        }
    const int count = static_cast<int>(faces.size());
    for (int i = 0; i < count; ++i) node_[faces[i]] = i;
    const int source = count, sink = count + 1;  // source: label a, sink: label b

    FlowGraph graph(count + 2);
    const double infinite = 1e30;
    for (int i = 0; i < count; ++i) {
        const int f = faces[i];
        bool fixed = ring_[f] == 0 || anchored_[f];
        for (int e = g.begin(f); e < g.end(f) && !fixed; ++e) fixed = !in_pair(g.neighbor[e]);  // touches a third region
        if (fixed) {
            if (labels_[f] == a) add_arc(graph, source, i, infinite, 0);
            else add_arc(graph, i, sink, infinite, 0);
            continue;
        }
        const double da = errors_(f, a), db = errors_(f, b), sum = da + db;
        // Cutting source→i puts i on b's side: it costs b's share, and the reverse.
        const double cost_b = sum > 0 ? db / sum : 0.5, cost_a = sum > 0 ? da / sum : 0.5;
        add_arc(graph, source, i, cost_b, 0);
        add_arc(graph, i, sink, cost_a, 0);
    }
    for (int i = 0; i < count; ++i) {
        const int f = faces[i];
        for (int e = g.begin(f); e < g.end(f); ++e) {
            const int j = node_[g.neighbor[e]];
            if (j <= i) continue;  // each dual edge once, and only between nodes
            // A boundary along a sharp crease costs nothing: that is where faces meet.
            const double length = crease_ && (*crease_)[e] ? 0.0 : g.edge_length[e];
            const double w = options_.lambda * length / (length + mean_edge_length_);
            add_arc(graph, i, j, w, w);
        }
    }
    boost::boykov_kolmogorov_max_flow(graph, source, sink);

    // The source's tree (black) is what stays reachable from it: label a.
    // The cut trades distance for boundary length in ratios; it is kept only if the band's
    // distance to its proxies grows by at most a half (two proxies that both fit a face
    // almost exactly make every ratio a coin toss).
    auto color = boost::get(boost::vertex_color, graph);
    double before = 0, after = 0;
    for (int i = 0; i < count; ++i) {
        const int f = faces[i];
        if (ring_[f] == 0) continue;
        const int label = color[i] == boost::black_color ? a : b;
        before += errors_(f, labels_[f]);
        after += errors_(f, label);
    }
    const bool keep = after <= 1.5 * before + 1e-300;
    for (int i = 0; i < count; ++i) {
        const int f = faces[i];
        if (ring_[f] > 0 && keep) labels_[f] = color[i] == boost::black_color ? a : b;
        ring_[f] = 0;
        node_[f] = -1;
    }
}

void BoundarySmoother::reconnect() {
    const DualGraph& g = model_.graph;
    const int n = model_.face_count();
    // Pieces of each region; every piece but the largest joins its main neighbour.
    std::vector<int> piece(n, -1);
    std::vector<double> piece_area;
    std::vector<int> piece_label, stack;
    for (int f = 0; f < n; ++f) {
        if (piece[f] >= 0) continue;
        const int id = static_cast<int>(piece_area.size());
        piece_area.push_back(0);
        piece_label.push_back(labels_[f]);
        piece[f] = id;
        stack.push_back(f);
        while (!stack.empty()) {
            const int h = stack.back();
            stack.pop_back();
            piece_area[id] += model_.areas[h];
            for (int e = g.begin(h); e < g.end(h); ++e) {
                const int m = g.neighbor[e];
                if (piece[m] < 0 && labels_[m] == labels_[h]) piece[m] = id, stack.push_back(m);
            }
        }
    }
    std::map<int, int> largest;  // label → piece
    for (int p = 0; p < static_cast<int>(piece_area.size()); ++p) {
        auto it = largest.find(piece_label[p]);
        if (it == largest.end() || piece_area[p] > piece_area[it->second]) largest[piece_label[p]] = p;
    }
    for (int p = 0; p < static_cast<int>(piece_area.size()); ++p) {
        if (largest[piece_label[p]] == p) continue;
        // Edges across a crease count only where the piece has no other: a piece cut off a
        // fillet by the cut continues into the fillet, not into the plane it meets at a crease.
        std::map<int, std::pair<int, int>> shared;  // neighbouring label → (smooth, all) shared edges
        for (int f = 0; f < n; ++f)
            if (piece[f] == p)
                for (int e = g.begin(f); e < g.end(f); ++e)
                    if (piece[g.neighbor[e]] != p) {
                        auto& [smooth, all] = shared[labels_[g.neighbor[e]]];
                        smooth += !crease_ || !(*crease_)[e];
                        ++all;
                    }
        int best = -1;
        std::pair<int, int> best_count{0, 0};
        for (const auto& [label, edges] : shared)
            if (edges > best_count) best = label, best_count = edges;
        if (best < 0) continue;  // an isolated piece (its own component): keep it
        for (int f = 0; f < n; ++f)
            if (piece[f] == p) labels_[f] = best;
    }
}

}  // namespace vqsa
