// vqsa command line: approximate a mesh by quadric proxies and write a report.
#include "lloyd/engine.h"
#include "examples.h"
#include "export/gltf_export.h"
#include "io/mesh_io.h"
#include "io/mesh_write.h"
#include "export/report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

namespace {

const char* kUsage =
    "usage: vqsa INPUT [options]\n"
    "  INPUT                 .off .obj .ply .stl .gltf .glb, or example:NAME (turned_part, capsule,\n"
    "                        closed_cylinder, axle)\n"
    "  --proxies N           stop at N proxies (default 20 unless --tolerance is given)\n"
    "  --tolerance T         stop when the RMS distance, relative to the longest bounding-box side, is below T\n"
    "  --max-iterations K    cap on Lloyd iterations (default 2000)\n"
    "  --seed S              seed for the initial faces (default 1)\n"
    "  --rings K             fuzzy band width for boundary smoothing, in face rings (default 1)\n"
    "  --lambda L            boundary-length weight of the smoothing (default 1)\n"
    "  --no-smooth           keep the Lloyd boundaries\n"
    "  --no-refit            keep general quadrics (no plane/sphere/cylinder/cone refit)\n"
    "  --no-project          no projected mesh and no error metrics\n"
    "  --report FILE.json    write the JSON report\n"
    "  --labels FILE.txt     write one proxy id per input face\n"
    "  --projected FILE      write the projected mesh (.obj, .ply or .off)\n"
    "  -o, --output FILE.glb write the result as binary glTF with per-region quadric metadata\n"
    "  --quiet               no progress lines\n";

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

double number(const std::string& flag, const char* text) {
    char* end = nullptr;
    const double v = std::strtod(text, &end);
    if (end == text || *end != '\0') throw UsageError(flag + " expects a number, not '" + text + "'");
    return v;
}

long long integer(const std::string& flag, const char* text) {
    char* end = nullptr;
    const long long v = std::strtoll(text, &end, 10);
    if (end == text || *end != '\0') throw UsageError(flag + " expects an integer, not '" + text + "'");
    return v;
}

struct Arguments {
    std::string input, report, labels, projected, glb;
    vqsa::EngineOptions options;
    bool quiet = false;
    bool default_proxies = false;  // no --proxies and no --tolerance: 20, or fewer on tiny meshes
};

Arguments parse(int argc, char** argv) {
    Arguments a;
    bool proxies_given = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> const char* {
            if (i + 1 >= argc) throw UsageError(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--proxies") {
            const long long n = integer(arg, value());
            if (n < 1 || n > 1000000) throw UsageError("--proxies must be between 1 and 1000000");
            a.options.proxies = static_cast<int>(n);
            proxies_given = true;
        } else if (arg == "--tolerance") {
            a.options.tolerance = number(arg, value());
            if (!(a.options.tolerance > 0) || a.options.tolerance >= 1) throw UsageError("--tolerance must be in (0, 1)");
        } else if (arg == "--max-iterations") {
            const long long n = integer(arg, value());
            if (n < 1 || n > 100000000) throw UsageError("--max-iterations must be at least 1");
            a.options.max_iterations = static_cast<int>(n);
        } else if (arg == "--seed") {
            const long long n = integer(arg, value());
            if (n < 0) throw UsageError("--seed must be non-negative");
            a.options.seed = static_cast<std::uint64_t>(n);
        } else if (arg == "--rings") {
            const long long n = integer(arg, value());
            if (n < 1 || n > 100) throw UsageError("--rings must be between 1 and 100");
            a.options.smoothing.rings = static_cast<int>(n);
        } else if (arg == "--lambda") {
            a.options.smoothing.lambda = number(arg, value());
            if (!(a.options.smoothing.lambda >= 0) || !std::isfinite(a.options.smoothing.lambda))
                throw UsageError("--lambda must be a non-negative number");
        } else if (arg == "--no-smooth") {
            a.options.smooth = false;
        } else if (arg == "--no-refit") {
            a.options.refit = false;
        } else if (arg == "--no-project") {
            a.options.project = false;
        } else if (arg == "--projected") {
            a.projected = value();
        } else if (arg == "-o" || arg == "--output") {
            a.glb = value();
        } else if (arg == "--report") {
            a.report = value();
        } else if (arg == "--labels") {
            a.labels = value();
        } else if (arg == "--quiet") {
            a.quiet = true;
        } else if (arg == "--help" || arg == "-h") {
            std::cout << kUsage;
            std::exit(0);
        } else if (!arg.empty() && arg[0] == '-') {
            throw UsageError("unknown option " + arg);
        } else if (a.input.empty()) {
            a.input = arg;
        } else {
            throw UsageError("more than one input: " + a.input + " and " + arg);
        }
    }
    if (a.input.empty()) throw UsageError("no input file");
    a.default_proxies = !proxies_given && a.options.tolerance == 0;
    return a;
}

void write_file(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error(path + ": cannot write the file");
}

}  // namespace

int main(int argc, char** argv) {
    using Clock = std::chrono::steady_clock;
    auto seconds = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); };
    Arguments args;
    try {
        args = parse(argc, argv);
    } catch (const UsageError& e) {
        std::cerr << "vqsa: " << e.what() << "\n" << kUsage;
        return 2;
    }
    try {
        const auto t0 = Clock::now();
        const std::string example = "example:";
        const vqsa::Mesh mesh = args.input.rfind(example, 0) == 0 ? vqsa::example_mesh(args.input.substr(example.size()))
                                                                 : vqsa::read_mesh_file(args.input);
        const auto t1 = Clock::now();
        if (args.default_proxies) args.options.proxies = static_cast<int>(std::min<std::size_t>(20, mesh.triangles.size()));
        vqsa::Engine engine(mesh, args.options);
        auto lloyd_end = t1;
        engine.run([&](const vqsa::ProgressEvent& e, const vqsa::Engine& eng) {
            if (lloyd_end == t1 && eng.lloyd_done()) lloyd_end = Clock::now();
            if (!args.quiet && e.phase != vqsa::Phase::lloyd && e.phase != vqsa::Phase::smooth)
                std::fprintf(stderr, "%-10s proxies %4d  iteration %5d  rms %.3e\n", vqsa::phase_name(e.phase),
                             e.proxies, e.iteration, e.rms);
            return true;
        });
        const auto t3 = Clock::now();
        if (lloyd_end == t1) lloyd_end = t3;
        const vqsa::Timing timing{seconds(t0, t1), seconds(t1, lloyd_end), seconds(lloyd_end, t3), seconds(t0, t3)};
        const nlohmann::json report = vqsa::make_report(mesh, engine, timing);
        if (!args.report.empty()) write_file(args.report, report.dump(1) + "\n");
        if (!args.labels.empty()) {
            std::string text;
            for (int l : engine.labels()) text += std::to_string(l) + "\n";
            write_file(args.labels, text);
        }
        std::printf("%s: %d faces, %d components -> %zu proxies (stopped: %s) in %d Lloyd iterations\n",
                    args.input.c_str(), mesh.input_face_count, engine.model().component_count, engine.proxies().size(),
                    vqsa::stop_reason_name(engine.stop_reason()), engine.iterations());
        std::printf("rms error %.4e (%.4e of the longest side), load %.3f s, Lloyd %.3f s, post-processing %.3f s\n",
                    engine.rms() * engine.model().frame.scale, engine.rms(), timing.load, timing.lloyd, timing.postprocess);
        if (const auto& m = engine.metrics())
            std::printf("projected surface vs input: rms %.4e, hausdorff %.4e (of the bounding-box diagonal)\n", m->rms,
                        m->hausdorff);
        if (!args.glb.empty()) write_file(args.glb, vqsa::export_glb(mesh, engine));
        if (!args.projected.empty()) {
            const std::vector<vqsa::Vec3> projected = engine.projected_vertices();
            if (projected.empty()) throw std::runtime_error("no projected mesh (projection was cancelled)");
            write_file(args.projected, vqsa::write_mesh(args.projected, projected, mesh.triangles));
        }
        for (const auto& p : report["proxies"])
            std::printf("  %3d %-24s faces %6d  rms %.3e\n", p["id"].get<int>(), p["type"].get<std::string>().c_str(),
                        p["faces"].get<int>(), p["rms_error"].get<double>());
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "vqsa: " << e.what() << "\n";
        return 1;
    }
}
