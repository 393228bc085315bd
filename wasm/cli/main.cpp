// vqsa command line: approximate a mesh by quadric proxies and write what was asked for.
// The same source builds natively and, for `npm run cli:wasm`, as WebAssembly under node.
#include "examples.h"
#include "export/gltf_export.h"
#include "export/report.h"
#include "io/mesh_io.h"
#include "io/mesh_write.h"
#include "pipeline/pipeline.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace {

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::string usage() {
    std::ostringstream out;
    out << "usage: vqsa INPUT [options]\n"
           "  INPUT                 .off .obj .ply .stl .gltf .glb, or example:NAME (";
    const auto names = vqsa::example_names();
    for (std::size_t i = 0; i < names.size(); ++i) out << (i ? ", " : "") << names[i];
    out << ")\n";
    const vqsa::Options defaults;
    for (const vqsa::OptionSpec& spec : vqsa::option_schema()) {
        std::string flag = "--" + spec.name;
        const nlohmann::json value = spec.get(defaults);
        std::string help = spec.help;
        if (spec.kind == vqsa::OptionKind::boolean) {
            if (value.get<bool>()) flag = "--no-" + spec.name, help = "do not " + help;
        } else {
            flag += spec.kind == vqsa::OptionKind::count     ? " N|auto"
                    : spec.kind == vqsa::OptionKind::integer ? " N"
                    : spec.kind == vqsa::OptionKind::choice  ? " WORD"
                                                             : " X";
            std::ostringstream shown;
            if (value.is_string()) shown << value.get<std::string>();
            else shown << value.get<double>();  // 1, 0.002: the shortest form
            help += " (default " + shown.str() + ")";
        }
        out << "  " << flag << std::string(flag.size() < 22 ? 22 - flag.size() : 1, ' ') << help << "\n";
    }
    out << "  --report FILE.json    write the JSON report\n"
           "  --labels FILE.txt     write one proxy id per input face\n"
           "  --projected FILE      write the projected mesh (.obj, .ply or .off)\n"
           "  --edits FILE.json     apply these edits after the run (docs/EDITS.md; a report's \"edits\" too)\n"
           "  -o, --output FILE.glb write the result as binary glTF with per-region quadric metadata\n"
           "  --glb-colours WORD    colour the GLB's regions each its own ('region', default) or by quadric type ('type')\n"
           "  --quiet               no progress lines\n";
    return out.str();
}

struct Arguments {
    std::string input, report, labels, projected, glb, edits;
    vqsa::GlbColours glb_colours = vqsa::GlbColours::region;
    vqsa::Options options;
    bool quiet = false;
};

Arguments parse(int argc, char** argv) {
    Arguments a;
    nlohmann::json given = nlohmann::json::object();
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw UsageError(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--help" || arg == "-h") {
            std::cout << usage();
            std::exit(0);
        } else if (arg == "--report") {
            a.report = value();
        } else if (arg == "--labels") {
            a.labels = value();
        } else if (arg == "--projected") {
            a.projected = value();
        } else if (arg == "--edits") {
            a.edits = value();
        } else if (arg == "-o" || arg == "--output") {
            a.glb = value();
        } else if (arg == "--glb-colours") {
            try {
                a.glb_colours = vqsa::glb_colours_from(value());
            } catch (const std::invalid_argument& e) {
                throw UsageError(e.what());
            }
        } else if (arg == "--quiet") {
            a.quiet = true;
        } else if (arg.rfind("--", 0) == 0) {
            // Schema options: --name VALUE, and --name / --no-name for booleans.
            const bool negated = arg.rfind("--no-", 0) == 0;
            const std::string name = arg.substr(negated ? 5 : 2);
            const vqsa::OptionSpec* spec = nullptr;
            for (const vqsa::OptionSpec& s : vqsa::option_schema())
                if (s.name == name) spec = &s;
            if (!spec || (negated && spec->kind != vqsa::OptionKind::boolean)) throw UsageError("unknown option " + arg);
            given[name] = spec->kind == vqsa::OptionKind::boolean ? nlohmann::json(!negated) : nlohmann::json(value());
        } else if (!arg.empty() && arg[0] == '-') {
            throw UsageError("unknown option " + arg);
        } else if (a.input.empty()) {
            a.input = arg;
        } else {
            throw UsageError("more than one input: " + a.input + " and " + arg);
        }
    }
    if (a.input.empty()) throw UsageError("no input file");
    try {
        a.options = vqsa::options_from_json(given);
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--") + e.what());
    }
    return a;
}

std::vector<vqsa::Edit> read_edits(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot read the file");
    try {
        return vqsa::edits_from_json(nlohmann::json::parse(in));
    } catch (const nlohmann::json::exception&) {
        throw std::runtime_error(path + ": not JSON");
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(path + ": " + e.what());
    }
}

void write_file(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error(path + ": cannot write the file");
}

}  // namespace

int main(int argc, char** argv) {
    Arguments args;
    try {
        args = parse(argc, argv);
    } catch (const UsageError& e) {
        std::cerr << "vqsa: " << e.what() << "\n" << usage();
        return 2;
    }
    try {
        const auto t0 = std::chrono::steady_clock::now();
        const std::string example = "example:";
        const vqsa::Mesh mesh = args.input.rfind(example, 0) == 0 ? vqsa::example_mesh(args.input.substr(example.size()))
                                                                 : vqsa::read_mesh_file(args.input);
        const double load = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const std::vector<vqsa::Edit> edits = args.edits.empty() ? std::vector<vqsa::Edit>{} : read_edits(args.edits);
        vqsa::Pipeline pipeline(mesh, args.options);
        std::string last_phase;
        const auto progress = [&](const vqsa::Progress& p) {
            const std::string phase = p.phase;
            if (!args.quiet && phase != "lloyd" && phase != "smooth" && phase != last_phase)
                std::fprintf(stderr, "%-10s proxies %4d  iteration %5d  rms %.3e\n", p.phase, p.proxies, p.iterations, p.rms);
            last_phase = phase;
            return true;
        };
        pipeline.run(progress);
        for (std::size_t i = 0; i < edits.size(); ++i) {
            try {
                pipeline.edit(edits[i]);
            } catch (const std::invalid_argument& e) {
                throw std::runtime_error(args.edits + ": edit " + std::to_string(i) + " (" + vqsa::edit_to_json(edits[i]).dump() +
                                         "): " + e.what());
            }
            pipeline.run(progress);
        }
        const vqsa::Result result = pipeline.result(load);
        if (!args.report.empty()) write_file(args.report, vqsa::make_report(result).dump(1) + "\n");
        if (!args.labels.empty()) {
            std::string text;
            for (int l : result.labels) text += std::to_string(l) + "\n";
            write_file(args.labels, text);
        }
        std::printf("%s: %d faces, %d components -> %zu proxies (stopped: %s) in %d Lloyd iterations\n",
                    args.input.c_str(), result.input.faces, result.input.components, result.proxies.size(),
                    vqsa::stop_reason_name(result.stop_reason), result.iterations);
        std::printf("rms error %.4e (%.4e of the longest side), load %.3f s, Lloyd %.3f s, post-processing %.3f s\n",
                    result.rms_error, result.rms_error_relative, result.timing.load, result.timing.lloyd,
                    result.timing.postprocess);
        for (std::size_t i = 0; i < result.edits.size(); ++i)
            std::printf("edit %zu %s: %.3f s\n", i, vqsa::edit_to_json(result.edits[i]).dump().c_str(), result.timing.edits[i]);
        if (const auto& m = result.metrics)
            std::printf("projected surface vs input: rms %.4e, hausdorff %.4e (of the bounding-box diagonal)\n", m->rms,
                        m->hausdorff);
        if (!args.glb.empty()) write_file(args.glb, vqsa::export_glb(mesh, result, args.glb_colours));
        if (!args.projected.empty()) {
            if (result.projected.empty()) throw std::runtime_error("no projected mesh (projection was off or cancelled)");
            write_file(args.projected, vqsa::write_mesh(args.projected, result.projected, mesh.triangles));
        }
        for (const vqsa::ProxyResult& p : result.proxies)
            std::printf("  %3d %-24s faces %6d  rms %.3e%s\n", p.id, vqsa::type_name(p.type), p.faces, p.rms_error,
                        p.locked ? "  locked" : "");
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "vqsa: " << e.what() << "\n";
        return 1;
    }
}
