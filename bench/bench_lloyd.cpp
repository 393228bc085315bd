// Times the Lloyd stage (building the model and everything up to the proxy count) on the
// shared meshes: `vqsa_bench [MESH_DIR] [RUNS]`. Prints the median of RUNS runs.
#include "geometry/model.h"
#include "io/mesh_io.h"
#include "lloyd/lloyd.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : "../shared/meshes";
    const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
    const std::pair<const char*, int> cases[] = {{"fandisk.off", 22}, {"bunny_closed.off", 28}};
    std::printf("%-18s %7s %7s %10s %7s %12s\n", "mesh", "faces", "proxies", "lloyd_s", "iters", "rms_rel");
    for (const auto& [name, proxies] : cases) {
        const vqsa::Mesh mesh = vqsa::read_mesh_file(dir + "/" + name);
        std::vector<double> times;
        int iterations = 0;
        double rms = 0;
        for (int r = 0; r < runs; ++r) {
            const auto t0 = std::chrono::steady_clock::now();
            const vqsa::Model model = vqsa::make_model(mesh);
            vqsa::LloydOptions options;
            options.proxies = proxies;
            vqsa::Lloyd lloyd(model, options);
            while (lloyd.step()) {
            }
            times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
            iterations = lloyd.iterations();
            rms = lloyd.rms();
        }
        std::sort(times.begin(), times.end());
        std::printf("%-18s %7zu %7d %10.3f %7d %12.4e\n", name, mesh.triangles.size(), proxies, times[times.size() / 2],
                    iterations, rms);
    }
    return 0;
}
