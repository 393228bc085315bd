#include "lloyd/flooding.h"

#include <cstring>

namespace vqsa {

namespace {

template <class Entry>
void heap_push(std::vector<Entry>& heap, const Entry& e) {
    heap.push_back(e);
    std::size_t i = heap.size() - 1;
    while (i > 0) {
        const std::size_t parent = (i - 1) / 2;
        if (!(heap[parent] > e)) break;
        heap[i] = heap[parent];
        i = parent;
    }
    heap[i] = e;
}

template <class Entry>
Entry heap_pop(std::vector<Entry>& heap_) {
    // Bottom-up: the hole at the root goes down to a leaf along the smaller children (one
    // comparison per level), then the last entry rises from there; it belongs near the
    // bottom, so this compares less than sifting it down. Same order, same pops.
    const Entry top = heap_.front();
    const Entry last = heap_.back();
    heap_.pop_back();
    const std::size_t n = heap_.size();
    if (n == 0) return top;
    std::size_t i = 0;
    for (std::size_t child = 1; child < n; child = 2 * i + 1) {
        if (child + 1 < n && heap_[child] > heap_[child + 1]) ++child;
        heap_[i] = heap_[child];
        i = child;
    }
    while (i > 0) {
        const std::size_t parent = (i - 1) / 2;
        if (!(heap_[parent] > last)) break;
        heap_[i] = heap_[parent];
        i = parent;
    }
    heap_[i] = last;
    return top;
}

}  // namespace

void Flooding::push(const Entry& e) {
    if (!heap_.empty() && heap_.front() > e) heap_push(near_, e);
    else heap_push(heap_, e);
}

Flooding::Entry Flooding::pop() {
    if (!near_.empty() && (heap_.empty() || heap_.front() > near_.front())) return heap_pop(near_);
    return heap_pop(heap_);
}

void Flooding::run(const Model& model, FaceErrors& errors, const std::vector<int>& seeds, std::vector<int>& labels,
                   const std::vector<char>* crease) {
    const DualGraph& graph = model.graph;
    queued_.assign(2 * labels.size(), -1);
    crossed_.assign(labels.size(), 0);
    heap_.clear();
    near_.clear();
    constexpr std::uint64_t kCrossed = std::uint64_t{1} << 63;

    auto queue_neighbours = [&](int face, int proxy) {
        for (int e = graph.begin(face); e < graph.end(face); ++e) {
            const int n = graph.neighbor[e];
            if (labels[n] >= 0) continue;
            const int crossed = crossed_[face] || (crease && (*crease)[e]);
            const int code = 2 * proxy + crossed;
            if (queued_[2 * n] == 2 * proxy || queued_[2 * n + 1] == 2 * proxy || queued_[2 * n] == code ||
                queued_[2 * n + 1] == code)
                continue;
            queued_[2 * n + 1] = queued_[2 * n];
            queued_[2 * n] = code;
            const float error = static_cast<float>(errors(n, proxy));
            std::uint32_t bits;
            std::memcpy(&bits, &error, sizeof bits);
            push({(crossed ? kCrossed : 0) | std::uint64_t{bits} << 32 | static_cast<std::uint32_t>(n), proxy});
        }
    };

    for (std::size_t p = 0; p < seeds.size(); ++p)
        if (seeds[p] >= 0) labels[seeds[p]] = static_cast<int>(p);
    for (std::size_t p = 0; p < seeds.size(); ++p)
        if (seeds[p] >= 0) queue_neighbours(seeds[p], static_cast<int>(p));
    while (!heap_.empty() || !near_.empty()) {
        const Entry e = pop();
        const int face = static_cast<int>(e.key & 0xffffffffu);
        if (labels[face] >= 0) continue;
        labels[face] = e.proxy;
        crossed_[face] = (e.key & kCrossed) != 0;
        queue_neighbours(face, e.proxy);
    }
}

}  // namespace vqsa
