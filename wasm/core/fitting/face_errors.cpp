#include "fitting/face_errors.h"

#include "fitting/distance.h"

namespace vqsa {

void FaceErrors::reset(const Model& model, std::vector<Quadric> proxies) {
    model_ = &model;
    proxies_ = std::move(proxies);
    hessian_norms_.resize(proxies_.size());
    for (std::size_t p = 0; p < proxies_.size(); ++p) hessian_norms_[p] = proxies_[p].hessian_norm();
    if (tag_.size() != model.points.size()) {
        tag_.assign(model.points.size(), ~std::uint64_t{0});
        distance2_.assign(model.points.size(), 0.0);
    }
    ++generation_;
    known_labels_ = nullptr;
    known_errors_ = nullptr;
}

double FaceErrors::vertex_distance2(int vertex, int proxy) {
    const std::uint64_t tag = generation_ << 32 | static_cast<std::uint32_t>(proxy);
    if (tag_[vertex] != tag) {
        const double d = taubin_distance(proxies_[proxy], hessian_norms_[proxy], model_->points[vertex]);
        distance2_[vertex] = d * d;
        tag_[vertex] = tag;
    }
    return distance2_[vertex];
}

double FaceErrors::compute(int face, int proxy) {
    const Triangle& t = model_->triangles[face];
    const double g = taubin_distance(proxies_[proxy], hessian_norms_[proxy], model_->barycentres[face]);
    return 0.25 * model_->areas[face] *
           (vertex_distance2(t[0], proxy) + vertex_distance2(t[1], proxy) + vertex_distance2(t[2], proxy) + g * g);
}

}  // namespace vqsa
