#include "lloyd/flooding.h"

#include <cstring>

namespace vqsa {

namespace {

constexpr std::uint64_t kCrossed = std::uint64_t{1} << 63;
constexpr std::uint64_t kNone = ~std::uint64_t{0};

std::uint32_t float_bits(double error) {
    const float e = static_cast<float>(error);
    std::uint32_t bits;
    std::memcpy(&bits, &e, sizeof bits);
    return bits;
}

void heap_push(std::vector<std::uint64_t>& heap, std::uint64_t key) {
    heap.push_back(key);
    std::size_t i = heap.size() - 1;
    while (i > 0) {
        const std::size_t parent = (i - 1) / 2;
        if (heap[parent] <= key) break;
        heap[i] = heap[parent];
        i = parent;
    }
    heap[i] = key;
}

std::uint64_t heap_pop(std::vector<std::uint64_t>& heap) {
    // Bottom-up: the hole at the root goes down to a leaf along the smaller children, then
    // the last key rises from there; it belongs near the bottom, so this compares less
    // than sifting it down. Which child is smaller is an add, not a branch: it is a coin
    // toss the predictor loses half the time.
    const std::uint64_t top = heap.front();
    const std::uint64_t last = heap.back();
    heap.pop_back();
    const std::size_t n = heap.size();
    if (n == 0) return top;
    std::uint64_t* h = heap.data();
    std::size_t i = 0;
    for (std::size_t child = 1; child < n; child = 2 * i + 1) {
        if (child + 1 < n) child += h[child + 1] < h[child];
        h[i] = h[child];
        i = child;
    }
    while (i > 0) {
        const std::size_t parent = (i - 1) / 2;
        if (h[parent] <= last) break;
        h[i] = h[parent];
        i = parent;
    }
    h[i] = last;
    return top;
}

}  // namespace

void Flooding::push(std::uint64_t key) {
    if (!heap_.empty() && key < heap_.front()) heap_push(near_, key);
    else heap_push(heap_, key);
}

std::uint64_t Flooding::pop() {
    if (!near_.empty() && (heap_.empty() || near_.front() < heap_.front())) return heap_pop(near_);
    return heap_pop(heap_);
}

void Flooding::run(const Model& model, FaceErrors& errors, const std::vector<int>& seeds, std::vector<int>& labels,
                   const std::vector<char>* crease) {
    const DualGraph& graph = model.graph;
    const int n = static_cast<int>(labels.size());
    faces_.resize(n);
    for (int f = 0; f < n; ++f) {
        Face& s = faces_[f];
        s.best = kNone, s.proxy = -1, s.label = labels[f];
        s.known_proxy = errors.known_proxy(f);
        s.known_bits = s.known_proxy >= 0 ? float_bits(errors.known_error(f)) : 0;
    }
    heap_.clear();
    near_.clear();

    auto queue_neighbours = [&](int face, int proxy, bool crossed_face) {
        for (int e = graph.begin(face); e < graph.end(face); ++e) {
            const int m = graph.neighbor[e];
            Face& s = faces_[m];
            if (s.label >= 0) continue;
            const bool crossed = crossed_face || (crease && (*crease)[e]);
            std::uint32_t bits;
            if (proxy == s.proxy) {
                // Queued by this proxy already, under a key no larger unless this path
                // crossed no crease and that one did.
                if (crossed || !(s.best & kCrossed)) continue;
                bits = static_cast<std::uint32_t>(s.best >> 32) & 0x7fffffffu;
            } else if (proxy == s.known_proxy) {
                bits = s.known_bits;
            } else {
                bits = float_bits(errors.compute(m, proxy));
            }
            const std::uint64_t key = (crossed ? kCrossed : 0) | std::uint64_t{bits} << 32 | static_cast<std::uint32_t>(m);
            if (key < s.best || (key == s.best && proxy < s.proxy)) {
                s.best = key, s.proxy = proxy;
                push(key);
            }
        }
    };

    for (std::size_t p = 0; p < seeds.size(); ++p)
        if (seeds[p] >= 0) faces_[seeds[p]].label = static_cast<int>(p);
    for (std::size_t p = 0; p < seeds.size(); ++p)
        if (seeds[p] >= 0) queue_neighbours(seeds[p], static_cast<int>(p), false);
    while (!heap_.empty() || !near_.empty()) {
        const std::uint64_t key = pop();
        const int face = static_cast<int>(key & 0xffffffffu);
        Face& s = faces_[face];
        if (s.label >= 0 || key != s.best) continue;
        s.label = s.proxy;
        queue_neighbours(face, s.proxy, (key & kCrossed) != 0);
    }
    for (int f = 0; f < n; ++f) labels[f] = faces_[f].label;
}

}  // namespace vqsa
