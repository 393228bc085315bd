// libFuzzer target for the whole pipeline on small meshes: load → approximate → smooth →
// classify and refit → project → measure → report → GLB. The first byte picks the proxy
// count, the second the format.
#include "export/gltf_export.h"
#include "export/report.h"
#include "io/mesh_io.h"
#include "pipeline/pipeline.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 3) return 0;
    static const char* const names[] = {"f.off", "f.obj", "f.ply", "f.stl", "f.glb"};
    try {
        const vqsa::Mesh mesh = vqsa::read_mesh(names[data[1] % 5], data + 2, size - 2);
        if (mesh.triangles.size() > 4000) return 0;  // small meshes: many executions
        vqsa::Options options;
        options.lloyd.proxies = std::min<int>(1 + data[0] % 8, static_cast<int>(mesh.triangles.size()));
        options.lloyd.max_iterations = 300;
        options.metrics.samples = 2000;
        vqsa::Pipeline pipeline(mesh, options);
        pipeline.run();
        const vqsa::Result result = pipeline.result();
        vqsa::make_report(result).dump();
        vqsa::export_glb(mesh, result);
    } catch (const vqsa::MeshReadError&) {
    }
    return 0;
}
