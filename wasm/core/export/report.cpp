#include "export/report.h"

#include <cmath>

namespace vqsa {

namespace {

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json options_report(const EngineOptions& o) {
    return {{"proxies", o.proxies},
            {"tolerance", o.tolerance},
            {"max_iterations", o.max_iterations},
            {"seed", o.seed},
            {"convergence", o.convergence},
            {"stage_iterations", o.stage_iterations},
            {"teleports", o.teleports},
            {"smooth", o.smooth},
            {"rings", o.smoothing.rings},
            {"lambda", o.smoothing.lambda},
            {"refit", o.refit}};
}

nlohmann::json params_report(const Classification& c) {
    nlohmann::json rotation = nlohmann::json::array();
    for (int r = 0; r < 3; ++r) rotation.push_back({c.rotation(r, 0), c.rotation(r, 1), c.rotation(r, 2)});
    switch (c.type) {
        case QuadricType::plane: return {{"point", vec(c.center)}, {"normal", vec(c.axis())}};
        case QuadricType::sphere: return {{"center", vec(c.center)}, {"radius", c.radius}};
        case QuadricType::cylinder: return {{"point", vec(c.center)}, {"axis", vec(c.axis())}, {"radius", c.radius}};
        case QuadricType::cone: return {{"apex", vec(c.center)}, {"axis", vec(c.axis())}, {"half_angle", c.half_angle}};
        case QuadricType::elliptic_paraboloid:
        case QuadricType::hyperbolic_paraboloid:
        case QuadricType::parabolic_cylinder:
            return {{"vertex", vec(c.center)}, {"rotation", rotation}, {"semi_axes", vec(c.semi_axes)}};
        default: return {{"center", vec(c.center)}, {"rotation", rotation}, {"semi_axes", vec(c.semi_axes)}};
    }
}

}  // namespace

nlohmann::json proxy_report(const Engine& engine, int i) {
    const Proxy& p = engine.proxies()[i];
    const Frame& frame = engine.model().frame;
    const Classification c = engine.classification(i);
    const Quadric q = engine.input_quadric(i);
    nlohmann::json out = {{"id", i},
                          {"type", p.quadric.is_plane() ? "plane" : type_name(c.type)},
                          {"special_fit", engine.is_special(i)},
                          {"coefficients", q.c},
                          {"faces", p.faces},
                          {"area", p.area * frame.scale * frame.scale},
                          {"rms_error", p.area > 0 ? std::sqrt(p.error / p.area) * frame.scale : 0.0},
                          {"params", params_report(c)}};
    if (const auto& m = engine.metrics())
        out["metrics"] = {{"rms", m->region_rms.at(i)}, {"hausdorff", m->region_hausdorff.at(i)}};
    return out;
}

nlohmann::json run_report(const Mesh& mesh, const Engine& engine) {
    const Model& model = engine.model();
    nlohmann::json run = {{"generator", "vqsa"},
                          {"version", VQSA_VERSION},
                          {"input",
                           {{"vertices", mesh.input_vertex_count},
                            {"faces", mesh.input_face_count},
                            {"faces_used", mesh.triangles.size()},
                            {"components", model.component_count},
                            {"bbox_diagonal", bounding_box(mesh).diagonal()},
                            {"bbox_longest_side", model.frame.scale}}},
                          {"options", options_report(engine.options())},
                          {"stop_reason", stop_reason_name(engine.stop_reason())},
                          {"iterations", engine.iterations()},
                          {"rms_error", engine.rms() * model.frame.scale},
                          {"rms_error_relative", engine.rms()}};
    if (const auto& m = engine.metrics()) run["metrics"] = {{"rms", m->rms}, {"hausdorff", m->hausdorff}};
    return run;
}

nlohmann::json make_report(const Mesh& mesh, const Engine& engine, const Timing& timing) {
    nlohmann::json report = run_report(mesh, engine);
    nlohmann::json proxies = nlohmann::json::array();
    for (int i = 0; i < static_cast<int>(engine.proxies().size()); ++i) proxies.push_back(proxy_report(engine, i));
    report["timing_s"] = {
        {"load", timing.load}, {"lloyd", timing.lloyd}, {"postprocess", timing.postprocess}, {"total", timing.total}};
    report["proxies"] = proxies;
    report["labels"] = engine.labels();
    report["labels_lloyd"] = engine.lloyd_labels();
    return report;
}

}  // namespace vqsa
