// CAD extraction on the procedural corpus (examples/cad_parts.h; --parts may also name
// parts beyond it, such as rounded_block): for every part and variant, the area accuracy
// under the best matching of regions to true faces at the true face count and with the
// automatic count, the regions lying on two parts of their quadric, and the time.
// `vqsa_cad [--parts a,b] [--variants clean,noisy] [--detail X] [--json FILE]` (all flags: the usage line).
#include "cad_parts.h"
#include "export/gltf_export.h"
#include "ground_truth.h"
#include "pipeline/pipeline.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {

std::set<std::string> list(const std::string& text) {
    std::set<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) out.insert(item);
    return out;
}

// True type × found type over the regions matched to a true face, at the true count.
std::map<std::string, std::map<std::string, int>> confusion;
std::map<std::string, std::pair<int, int>> typed, typed_all;  // variant → (right, all): clean matches, all matches

struct Worst {
    int patches = 0;
    double axis = -1, radius = -1, half_angle = -1;  // degrees, relative, degrees (-1: no such parameter)
};
std::map<std::string, std::map<std::string, Worst>> worst;  // variant → true type → worst errors

struct Outcome {
    int proxies = 0;
    double accuracy = 0, seconds = 0;
    int two_part = 0;
    std::string stop;
};

std::string dump_dir;  // --dump: a GLB of every run, for bench/render.mjs
bool verbose = false;
int seed_offset = 0;  // --seed-offset: the same meshes, other seeds for the method's choices

Outcome run(const vqsa::Part& part, int proxies, std::uint64_t seed, const std::string& name,
            const std::string& variant = "") {
    vqsa::Options options;
    options.lloyd.proxies = proxies;
    options.lloyd.seed = seed;
    options.project = false;
    const auto t0 = std::chrono::steady_clock::now();
    vqsa::Pipeline pipeline(part.mesh, options);
    std::string last;
    pipeline.run([&](const vqsa::Progress& p) {
        if (verbose && p.phase != last && std::string(p.phase) != "lloyd")
            std::fprintf(stderr, "    %s %d proxies rms %.3e\n", p.phase, p.proxies, p.rms);
        last = p.phase;
        return true;
    });
    const vqsa::Result r = pipeline.result();
    Outcome o;
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    o.proxies = static_cast<int>(r.proxies.size());
    const vqsa::PartitionScore score = vqsa::score_partition(part, r.face_labels, o.proxies);
    o.accuracy = score.accuracy;
    o.two_part = vqsa::two_part_regions(part.mesh, r);
    o.stop = vqsa::stop_reason_name(r.stop_reason);
    if (!variant.empty()) {
        for (const vqsa::ProxyResult& p : r.proxies) {
            const int face = score.face_of[p.id];
            if (face < 0) continue;
            const std::string truth = vqsa::type_name(part.surfaces[face].type), found = vqsa::type_name(p.type);
            auto& [right_all, all_all] = typed_all[variant];
            right_all += truth == found, ++all_all;
            if (!score.clean_match[p.id]) continue;
            ++confusion[truth][found];
            if (truth == found) {
                // The worst parameter error per variant and true type, over the patches typed right.
                const vqsa::ParameterError e = vqsa::parameter_error(part.surfaces[face], p.shape);
                Worst& w = worst[variant][truth];
                ++w.patches;
                if (!std::isnan(e.axis_degrees)) w.axis = std::max(w.axis, e.axis_degrees);
                if (!std::isnan(e.radius_relative)) w.radius = std::max(w.radius, e.radius_relative);
                if (!std::isnan(e.half_angle_degrees)) w.half_angle = std::max(w.half_angle, e.half_angle_degrees);
            }
            if (truth != found && verbose)
                std::fprintf(stderr, "  %s: region %d (%d faces) is %s rms %.3e, runner-up %s rms %.3e\n", variant.c_str(), p.id,
                             p.faces, found.c_str(), p.type_rms, p.runner_up ? vqsa::type_name(p.runner_up->type) : "-",
                             p.runner_up ? p.runner_up->rms : 0.0);
            auto& [right, all] = typed[variant];
            right += truth == found, ++all;
        }
    }
    if (!dump_dir.empty()) std::ofstream(dump_dir + "/" + name + ".glb", std::ios::binary) << vqsa::export_glb(part.mesh, r);
    if (verbose) {
        std::fprintf(stderr, "%s: %d proxies, stopped %s, accuracy %.4f\n", name.c_str(), o.proxies, o.stop.c_str(), o.accuracy);
        // Where each region's faces come from: true face (triangles), the largest first.
        std::vector<std::map<int, int>> from(r.proxies.size());
        for (std::size_t t = 0; t < r.face_labels.size(); ++t)
            if (r.face_labels[t] >= 0) ++from[r.face_labels[t]][part.face[t]];
        for (const vqsa::ProxyResult& p : r.proxies) {
            const int face = score.face_of[p.id];
            std::fprintf(stderr, "  %2d %-22s faces %5d area %.4f rms %.2e  -> true %d %s", p.id, vqsa::type_name(p.type),
                         p.faces, p.area, p.rms_error, face, face >= 0 ? vqsa::type_name(part.surfaces[face].type) : "-");
            std::vector<std::pair<int, int>> sources(from[p.id].begin(), from[p.id].end());
            std::sort(sources.begin(), sources.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
            for (const auto& [f, n] : sources) std::fprintf(stderr, " %d:%d", f, n);
            std::fprintf(stderr, "\n");
        }
    }
    return o;
}

}  // namespace

// A bad argument or an unreadable mesh ends with its message, not std::terminate.
int main(int argc, char** argv) try {
    std::set<std::string> parts, variants;
    std::string json_path;
    bool pose = true;  // --pose 0: the canonical pose, easier to look at
    double detail = 1;  // --detail: every sample count scaled (0.4: a coarse CAD export's tessellation)
    double noise = -1;  // --noise: the noisy variant's σ, relative to the diagonal (-1: the corpus's own)
    const char* usage =
        "usage: vqsa_cad [--parts a,b] [--variants clean,noisy,irregular] [--json FILE] [--dump DIR] [--verbose 1] [--seed-offset K] [--detail X] [--noise X]\n";
    for (int i = 1; i < argc; i += 2) {
        const std::string flag = argv[i];
        if (i + 1 == argc) {
            std::cerr << usage;
            return 2;
        }
        if (flag == "--parts") parts = list(argv[i + 1]);
        else if (flag == "--variants") variants = list(argv[i + 1]);
        else if (flag == "--json") json_path = argv[i + 1];
        else if (flag == "--dump") dump_dir = argv[i + 1];
        else if (flag == "--pose") pose = std::string(argv[i + 1]) == "1";
        else if (flag == "--verbose") verbose = std::string(argv[i + 1]) == "1";
        else if (flag == "--seed-offset") seed_offset = std::stoi(argv[i + 1]);
        else if (flag == "--detail") detail = std::stod(argv[i + 1]);
        else if (flag == "--noise") noise = std::stod(argv[i + 1]);
        else {
            std::cerr << usage;
            return 2;
        }
    }
    nlohmann::json rows = nlohmann::json::array();
    std::printf("| part | variant | faces | triangles | accuracy (true count) | auto count | accuracy (auto) | two-part regions | time s |\n");
    std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
    double sum_true = 0, sum_auto = 0, min_true = 1, min_auto = 1;
    int cases = 0;
    std::vector<std::string> selected = vqsa::corpus_part_names();
    if (!parts.empty()) {
        selected.clear();
        for (const std::string& name : vqsa::part_names())
            if (parts.count(name)) selected.push_back(name);
    }
    for (const vqsa::CorpusCase& c : vqsa::cad_corpus(selected)) {
        if (!variants.empty() && !variants.count(c.variant)) continue;
        vqsa::PartOptions options = c.options;
        options.random_pose = pose;
        options.detail = detail;
        if (noise >= 0 && options.noise > 0) options.noise = noise;
        const vqsa::Part part = vqsa::make_part(c.part, options);
        const int faces = static_cast<int>(part.surfaces.size());
        const std::string name = c.part + "_" + c.variant;
        const std::uint64_t seed = c.options.seed + seed_offset;
        const Outcome truth = run(part, faces, seed, name + "_true", c.variant);
        const Outcome automatic = run(part, 0, seed, name + "_auto");
        std::printf("| %s | %s | %d | %zu | %.4f | %d | %.4f | %d | %.2f |\n", c.part.c_str(), c.variant.c_str(), faces,
                    part.mesh.triangles.size(), truth.accuracy, automatic.proxies, automatic.accuracy,
                    truth.two_part + automatic.two_part, truth.seconds + automatic.seconds);
        std::fflush(stdout);
        sum_true += truth.accuracy, sum_auto += automatic.accuracy, ++cases;
        min_true = std::min(min_true, truth.accuracy), min_auto = std::min(min_auto, automatic.accuracy);
        rows.push_back({{"part", c.part}, {"variant", c.variant}, {"faces", faces},
                        {"triangles", part.mesh.triangles.size()},
                        {"true_count", {{"accuracy", truth.accuracy}, {"two_part", truth.two_part}, {"seconds", truth.seconds}}},
                        {"auto", {{"proxies", automatic.proxies}, {"accuracy", automatic.accuracy},
                                  {"two_part", automatic.two_part}, {"seconds", automatic.seconds}, {"stop", automatic.stop}}}});
    }
    if (cases)
        std::printf("\nmean accuracy %.4f (true count), %.4f (auto); lowest %.4f, %.4f\n", sum_true / cases,
                    sum_auto / cases, min_true, min_auto);
    std::printf("\nTypes of the regions matched to a true face (sharing 90 %% of the area of each), at the true count (rows: true type, columns: found):\n\n");
    std::set<std::string> found_types;
    for (const auto& [truth, row] : confusion)
        for (const auto& [found, n] : row) found_types.insert(found);
    std::printf("| true \\ found |");
    for (const std::string& t : found_types) std::printf(" %s |", t.c_str());
    std::printf("\n|---|");
    for (std::size_t i = 0; i < found_types.size(); ++i) std::printf("---:|");
    std::printf("\n");
    for (const auto& [truth, row] : confusion) {
        std::printf("| %s |", truth.c_str());
        for (const std::string& t : found_types) std::printf(" %d |", row.count(t) ? row.at(t) : 0);
        std::printf("\n");
    }
    std::printf("\n");
    for (const auto& [variant, counts] : typed)
        std::printf("typed right (%s): %d of %d (%.1f %%) of the clean matches, %d of %d (%.1f %%) of all matches\n",
                    variant.c_str(), counts.first, counts.second, 100.0 * counts.first / std::max(1, counts.second),
                    typed_all[variant].first, typed_all[variant].second,
                    100.0 * typed_all[variant].first / std::max(1, typed_all[variant].second));
    std::printf("\nWorst parameter error over the patches typed right (axis: plane normal, cylinder or cone axis):\n\n");
    std::printf("| variant | type | patches | axis ° | radius %% | half-angle ° |\n|---|---|---:|---:|---:|---:|\n");
    auto cell = [](double value, double scale) {
        char text[32] = "-";
        if (value >= 0) std::snprintf(text, sizeof text, "%.3f", scale * value);
        return std::string(text);
    };
    for (const auto& [variant, types] : worst)
        for (const auto& [type, w] : types)
            std::printf("| %s | %s | %d | %s | %s | %s |\n", variant.c_str(), type.c_str(), w.patches, cell(w.axis, 1).c_str(),
                        cell(w.radius, 100).c_str(), cell(w.half_angle, 1).c_str());
    if (!json_path.empty()) std::ofstream(json_path) << rows.dump(1) << "\n";
    return 0;
} catch (const std::invalid_argument&) {
    std::cerr << "vqsa_cad: an option's value is not a number\n";
    return 2;
} catch (const std::exception& e) {
    std::cerr << "vqsa_cad: " << e.what() << "\n";
    return 1;
}
