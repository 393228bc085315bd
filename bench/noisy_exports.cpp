// A real CAD export made noisy: Gaussian noise along the normals (examples'
// add_normal_noise, as the corpus's noisy parts), σ relative to the diagonal, several
// draws, each run with the automatic count and held to the clean export's own automatic
// partition (area in its matched region, best one-to-one matching) and to its crease
// charts (area of each region in its largest clean chart).
// `vqsa_noisy MESH [--noise 0.001,0.002] [--draws 3]`
#include "cad_parts.h"
#include "geometry/features.h"
#include "geometry/model.h"
#include "ground_truth.h"
#include "io/mesh_io.h"
#include "pipeline/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

vqsa::Result automatic(const vqsa::Mesh& mesh) {
    vqsa::Options options;
    options.lloyd.proxies = 0;
    options.project = false;
    vqsa::Pipeline pipeline(mesh, options);
    pipeline.run({});
    return pipeline.result();
}

}  // namespace

// A bad argument or an unreadable mesh ends with its message, not std::terminate.
int main(int argc, char** argv) try {
    const char* usage = "usage: vqsa_noisy MESH [--noise 0.001,0.002] [--draws 3]\n";
    if (argc < 2) {
        std::cerr << usage;
        return 2;
    }
    std::vector<double> levels{0.001, 0.002};
    int draws = 3;
    for (int i = 2; i < argc; i += 2) {
        const std::string flag = argv[i];
        if (i + 1 == argc) {
            std::cerr << usage;
            return 2;
        }
        if (flag == "--noise") {
            levels.clear();
            std::stringstream in(argv[i + 1]);
            for (std::string item; std::getline(in, item, ',');) levels.push_back(std::stod(item));
        } else if (flag == "--draws") {
            draws = std::stoi(argv[i + 1]);
        } else {
            std::cerr << usage;
            return 2;
        }
    }
    const vqsa::Mesh clean = vqsa::read_mesh_file(argv[1]);
    const vqsa::Result truth = automatic(clean);
    const vqsa::Model model = vqsa::make_model(clean);
    const vqsa::Features charts = vqsa::detect_features(model);
    std::printf("%s: %zu faces, clean: %zu regions, %d charts\n\n", argv[1], clean.triangles.size(),
                truth.proxies.size(), charts.chart_count);
    std::printf("| σ, %% of diagonal | draw | charts | regions | stop | iterations | area in its clean region | area in one clean chart | time s |\n");
    std::printf("|---:|---:|---:|---:|---|---:|---:|---:|---:|\n");
    vqsa::Part part{"export", clean, truth.face_labels, std::vector<vqsa::TrueSurface>(truth.proxies.size())};
    for (double noise : levels)
        for (int draw = 1; draw <= draws; ++draw) {
            part.mesh = clean;
            vqsa::add_normal_noise(part.mesh, noise, static_cast<std::uint64_t>(draw));
            const auto t0 = std::chrono::steady_clock::now();
            const vqsa::Result r = automatic(part.mesh);
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            const vqsa::PartitionScore score =
                vqsa::score_partition(part, r.face_labels, static_cast<int>(r.proxies.size()));
            const double within = vqsa::area_within_one_chart(model, charts.chart, r.face_labels,
                                                              static_cast<int>(r.proxies.size()));
            const int noisy_charts = vqsa::detect_features(vqsa::make_model(part.mesh)).chart_count;
            std::printf("| %.3f | %d | %d | %zu | %s | %d | %.4f | %.4f | %.1f |\n", 100 * noise, draw, noisy_charts,
                        r.proxies.size(), vqsa::stop_reason_name(r.stop_reason), r.iterations, score.accuracy,
                        within, seconds);
            std::fflush(stdout);
        }
    return 0;
} catch (const std::invalid_argument&) {
    std::cerr << "vqsa_noisy: an option's value is not a number\n";
    return 2;
} catch (const std::exception& e) {
    std::cerr << "vqsa_noisy: " << e.what() << "\n";
    return 1;
}
