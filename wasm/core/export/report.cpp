#include "export/report.h"

#include <cmath>

namespace vqsa {

namespace {

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

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
        case QuadricType::intersecting_planes: {
            // Both planes, through the common line.
            const Vec3 e0 = c.rotation.col(0), e1 = c.rotation.col(1);
            const Vec3 n1 = (e0 / c.semi_axes[0] - e1 / c.semi_axes[1]).normalized();
            const Vec3 n2 = (e0 / c.semi_axes[0] + e1 / c.semi_axes[1]).normalized();
            return {{"line_point", vec(c.center)},
                    {"line_direction", vec(c.axis())},
                    {"planes", {{{"point", vec(c.center)}, {"normal", vec(n1)}}, {{"point", vec(c.center)}, {"normal", vec(n2)}}}}};
        }
        case QuadricType::parallel_planes: {
            const Vec3 n = c.axis(), offset = c.semi_axes[2] * n;
            return {{"planes", {{{"point", vec(c.center + offset)}, {"normal", vec(n)}},
                                {{"point", vec(c.center - offset)}, {"normal", vec(n)}}}}};
        }
        case QuadricType::empty: return nlohmann::json::object();  // no real points: no parameters
        default: return {{"center", vec(c.center)}, {"rotation", rotation}, {"semi_axes", vec(c.semi_axes)}};
    }
}

}  // namespace

nlohmann::json proxy_report(const Result& result, int i) {
    const ProxyResult& p = result.proxies.at(i);
    nlohmann::json out = {{"id", p.id},
                          {"type", type_name(p.type)},
                          {"special_fit", p.special_fit},
                          {"coefficients", p.quadric.c},
                          {"faces", p.faces},
                          {"area", p.area},
                          {"rms_error", p.rms_error},
                          {"type_rms", p.type_rms},
                          {"runner_up", p.runner_up ? nlohmann::json{{"type", type_name(p.runner_up->type)}, {"rms", p.runner_up->rms}}
                                                    : nlohmann::json()},
                          {"params", params_report(p.shape)},
                          {"locked", p.locked},
                          {"imposed_type", p.imposed == ImposedType::none ? nlohmann::json() : nlohmann::json(imposed_type_name(p.imposed))}};
    if (const auto& m = result.metrics) {
        // No sample in the region: unmeasured, not an RMS of 0.
        const long samples = m->region_samples.at(i);
        out["metrics"] = {{"rms", samples > 0 ? nlohmann::json(m->region_rms.at(i)) : nlohmann::json()},
                          {"hausdorff", samples > 0 ? nlohmann::json(m->region_hausdorff.at(i)) : nlohmann::json()},
                          {"samples", samples}};
    }
    return out;
}

nlohmann::json run_report(const Result& result) {
    const InputInfo& in = result.input;
    nlohmann::json run = {{"generator", "vqsa"},
                          {"version", VQSA_VERSION},
                          {"input",
                           {{"vertices", in.vertices},
                            {"faces", in.faces},
                            {"faces_used", in.faces_used},
                            {"components", in.components},
                            {"bbox_diagonal", in.bbox_diagonal},
                            {"bbox_longest_side", in.bbox_longest_side}}},
                          {"options", options_to_json(result.options)},
                          {"stop_reason", stop_reason_name(result.stop_reason)},
                          {"iterations", result.iterations},
                          {"rms_error", result.rms_error},
                          {"rms_error_relative", result.rms_error_relative}};
    run["edits"] = nlohmann::json::array();
    for (const Edit& e : result.edits) run["edits"].push_back(edit_to_json(e));
    if (const auto& m = result.metrics)
        run["metrics"] = {{"rms", m->rms},
                          {"hausdorff", m->hausdorff},
                          {"rms_standard_error", m->rms_standard_error},
                          {"samples", m->samples}};
    return run;
}

nlohmann::json make_report(const Result& result) {
    nlohmann::json report = run_report(result);
    nlohmann::json proxies = nlohmann::json::array();
    for (int i = 0; i < static_cast<int>(result.proxies.size()); ++i) proxies.push_back(proxy_report(result, i));
    const Timing& t = result.timing;
    report["timing_s"] = {{"load", t.load},       {"lloyd", t.lloyd},     {"postprocess", t.postprocess},
                          {"smooth", t.smooth},   {"refit", t.refit},     {"project", t.project},
                          {"measure", t.measure}, {"total", t.total},     {"edits", t.edits}};
    report["proxies"] = proxies;
    report["labels"] = result.labels;
    report["labels_lloyd"] = result.lloyd_labels;
    return report;
}

}  // namespace vqsa
