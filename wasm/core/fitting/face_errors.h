// The triangle error d(t, P) of many faces against a set of proxies, with the distances
// of shared vertices remembered.
#pragma once

#include "fitting/quadric.h"
#include "geometry/model.h"

#include <cstdint>
#include <vector>

namespace vqsa {

// d(t, P) of faces against proxies, remembering each vertex's last squared distance:
// neighbouring faces of one region share vertices, so most are evaluated once.
class FaceErrors {
public:
    // Starts a new set of proxies (forgets every remembered distance).
    void reset(const Model& model, std::vector<Quadric> proxies);
    // Errors already known for these proxies: errors[f] is d(f, labels[f]). Both
    // arrays must stay alive and unchanged while they are in use.
    void know(const std::vector<int>& labels, const std::vector<double>& errors) {
        known_labels_ = &labels;
        known_errors_ = &errors;
    }
    double operator()(int face, int proxy) {
        if (known_proxy(face) == proxy) return (*known_errors_)[face];
        return compute(face, proxy);
    }
    // The proxy whose error at `face` is known (-1: none), and that error.
    int known_proxy(int face) const { return known_labels_ ? (*known_labels_)[face] : -1; }
    double known_error(int face) const { return (*known_errors_)[face]; }
    // d(face, proxy), evaluated (known errors aside).
    double compute(int face, int proxy);

private:
    double vertex_distance2(int vertex, int proxy);

    const Model* model_ = nullptr;
    std::vector<Quadric> proxies_;
    std::vector<double> hessian_norms_;
    std::vector<double> distance2_;
    std::vector<std::uint64_t> tag_;  // generation << 32 | proxy, for distance2_
    std::uint64_t generation_ = 0;
    const std::vector<int>* known_labels_ = nullptr;
    const std::vector<double>* known_errors_ = nullptr;
};

}  // namespace vqsa
