// Distortion-minimising flooding (ALGORITHM §3, after Cohen-Steiner et al. 2004).
#pragma once

#include "geometry/model.h"
#include "fitting/quadric.h"

#include <cstdint>
#include <vector>

namespace vqsa {

// d(t, P) of faces against proxies, remembering each vertex's last squared distance:
// neighbouring faces of one region share vertices, so most are evaluated once.
class FaceErrors {
public:
    // Starts a new set of proxies (forgets every remembered distance).
    void reset(const Model& model, const std::vector<Quadric>& proxies);
    // Errors already known for these proxies: errors[f] is d(f, labels[f]). Both
    // arrays must stay alive and unchanged while they are in use.
    void know(const std::vector<int>& labels, const std::vector<double>& errors) {
        known_labels_ = &labels;
        known_errors_ = &errors;
    }
    double operator()(int face, int proxy) {
        if (known_labels_ && (*known_labels_)[face] == proxy) return (*known_errors_)[face];
        return compute(face, proxy);
    }

private:
    double compute(int face, int proxy);
    double vertex_distance2(int vertex, int proxy);

    const Model* model_ = nullptr;
    const std::vector<Quadric>* proxies_ = nullptr;
    std::vector<double> hessian_norms_;
    std::vector<double> distance2_;
    std::vector<std::uint64_t> tag_;  // generation << 32 | proxy, for distance2_
    std::uint64_t generation_ = 0;
    const std::vector<int>* known_labels_ = nullptr;
    const std::vector<double>* known_errors_ = nullptr;
};

// Grows every proxy's region from its seed face, always taking next the unlabelled
// face with the smallest error to the region reaching it. Regions come out connected.
// The engine keeps one Flooding and reuses its storage, so a run does not allocate.
class Flooding {
public:
    // `labels`: faces with a label ≥ 0 are fixed and block the flood; the others must
    // be -1 and get the label of a seed that reaches them (or stay -1 if none does).
    // Seed faces must be unlabelled; seed i gets label i.
    void run(const Model& model, FaceErrors& errors, const std::vector<int>& seeds, std::vector<int>& labels);

private:
    struct Entry {
        // The error as float bits (monotone for non-negative floats) above the face
        // index, then the proxy: a strict total order, so every heap pops the same
        // sequence and native and WASM builds agree.
        std::uint64_t key;
        int proxy;
        bool operator>(const Entry& o) const { return key != o.key ? key > o.key : proxy > o.proxy; }
    };
    void push(const Entry& e);
    Entry pop();

    std::vector<Entry> heap_;
    // The last two proxies that queued each face: skips re-queuing a face for the
    // same proxy from another neighbour (the error would be the same).
    std::vector<int> queued_;
};

}  // namespace vqsa
