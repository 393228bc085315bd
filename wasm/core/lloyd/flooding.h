// Distortion-minimising flooding (docs/METHOD.md §2, after Cohen-Steiner et al. 2004).
#pragma once

#include "fitting/face_errors.h"
#include "geometry/model.h"

#include <cstdint>
#include <vector>

namespace vqsa {

// Grows every proxy's region from its seed face, always taking next the unlabelled
// face with the smallest error to the region reaching it. Regions come out connected.
// With creases, a face reached across one (or from a face that was) comes after every
// face reached without: each region fills its own chart before it spills into others.
// The engine keeps one Flooding and reuses its storage, so a run does not allocate.
class Flooding {
public:
    // `labels`: faces with a label ≥ 0 are fixed and block the flood; the others must
    // be -1 and get the label of a seed that reaches them (or stay -1 if none does).
    // Seed faces must be unlabelled; seed i gets label i. A seed of -1 grows nothing (a
    // region held fixed in `labels`).
    // `crease`: per dual-graph link, or null for none.
    void run(const Model& model, FaceErrors& errors, const std::vector<int>& seeds, std::vector<int>& labels,
             const std::vector<char>* crease = nullptr);

private:
    struct Entry {
        // Whether a crease was crossed (the float's free sign bit), the error as float
        // bits (monotone for non-negative floats), the face index, then the proxy: a
        // strict total order, so every heap pops the same sequence and native and WASM
        // builds agree.
        std::uint64_t key;
        int proxy;
        bool operator>(const Entry& o) const { return key != o.key ? key > o.key : proxy > o.proxy; }
    };
    void push(const Entry& e);
    Entry pop();

    // Entries below heap_'s top when queued go to the small near_ heap instead (pops take
    // the least of both tops: the same order). Neighbours of the face just taken often have
    // errors as low as it had, and are taken next: they skip the deep heap.
    std::vector<Entry> heap_;
    std::vector<Entry> near_;
    // The last two (proxy, crossed) that queued each face: skips re-queuing a face for
    // the same proxy from another neighbour (the error would be the same) unless the new
    // path crossed no crease and the old one did.
    std::vector<int> queued_;
    std::vector<char> crossed_;  // per labelled face: reached across a crease
};

}  // namespace vqsa
