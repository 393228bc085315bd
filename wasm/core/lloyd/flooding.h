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
    // A face is queued under the key: whether a crease was crossed (the float's free sign
    // bit), the error as float bits (monotone for non-negative floats), the face index;
    // ties between proxies go to the lower one. A strict total order, so every run takes
    // faces in the same sequence and native and WASM builds agree.
    //
    // Only a key below every key the face was queued under before goes into the heap: a
    // larger one would come out after the face was taken. So the heap holds keys alone,
    // and the proxy of a face's least key is kept with the face.
    struct Face {
        std::uint64_t best;  // least key queued (~0: none)
        int proxy;           // whose key `best` is
        int label;           // -1 until taken
        // The error already at hand (FaceErrors' known one: against the face's region
        // before this run), as float bits.
        int known_proxy;
        std::uint32_t known_bits;
    };
    void push(std::uint64_t key);
    std::uint64_t pop();

    // Per face in one record: the flood visits faces in no spatial order, and each visit
    // then costs one cache line instead of one per array.
    std::vector<Face> faces_;
    // Keys below heap_'s top when queued go to the small near_ heap instead (pops take the
    // least of both tops: the same order). Neighbours of the face just taken often have
    // errors as low as it had, and are taken next: they skip the deep heap.
    std::vector<std::uint64_t> heap_;
    std::vector<std::uint64_t> near_;
};

}  // namespace vqsa
