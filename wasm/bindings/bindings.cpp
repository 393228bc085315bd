// The engine for JavaScript (embind): typed arrays in and out, no per-element calls,
// and every C++ exception turned into a JS Error carrying its message.
#include "lloyd/engine.h"
#include "export/gltf_export.h"
#include "io/mesh_io.h"
#include "io/mesh_write.h"
#include "export/palette.h"
#include "export/report.h"
#include "shapes.h"
#include "examples.h"

#include <emscripten/bind.h>
#include <emscripten/emscripten.h>
#include <emscripten/val.h>

#include <memory>

using emscripten::val;

namespace vqsa {

namespace {

[[noreturn]] void throw_js(const std::string& message) { val::global("Error").new_(message).throw_(); }

template <typename F>
auto guarded(F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const std::bad_alloc&) {
        throw_js("out of memory: the mesh is too large for this browser");
    } catch (const std::length_error&) {  // a container past wasm32's 4 GB
        throw_js("out of memory: the mesh is too large for this browser");
    } catch (const std::exception& e) {
        throw_js(e.what());
    }
}

template <typename T>
val copy_to_js(const char* type, const std::vector<T>& data) {
    return val::global(type).new_(val(emscripten::typed_memory_view(data.size(), data.data())));
}

val bytes_to_js(const std::string& bytes) {
    return val::global("Uint8Array")
        .new_(val(emscripten::typed_memory_view(bytes.size(), reinterpret_cast<const unsigned char*>(bytes.data()))));
}

EngineOptions parse_options(const val& o) {
    EngineOptions options;
    const val keys = val::global("Object").call<val>("keys", o);
    const int n = keys["length"].as<int>();
    for (int i = 0; i < n; ++i) {
        const std::string key = keys[i].as<std::string>();
        const val v = o[key];
        if (v.isUndefined() || v.isNull()) continue;
        auto number = [&] {
            if (v.typeOf().as<std::string>() != "number") throw std::invalid_argument("option " + key + " must be a number");
            return v.as<double>();
        };
        auto integer = [&] {
            const double d = number();
            if (d != std::floor(d) || std::abs(d) > 2147483647.0) throw std::invalid_argument("option " + key + " must be an integer");
            return static_cast<int>(d);
        };
        if (key == "proxies") options.proxies = integer();
        else if (key == "tolerance") options.tolerance = number();
        else if (key == "maxIterations") options.max_iterations = integer();
        else if (key == "seed") {
            const double d = number();
            if (d < 0 || d != std::floor(d)) throw std::invalid_argument("option seed must be a non-negative integer");
            options.seed = static_cast<std::uint64_t>(d);
        } else if (key == "rings") options.smoothing.rings = integer();
        else if (key == "lambda") options.smoothing.lambda = number();
        else if (key == "smooth") options.smooth = v.as<bool>();
        else if (key == "refit") options.refit = v.as<bool>();
        else if (key == "project") options.project = v.as<bool>();
        else if (key == "measure") options.measure = v.as<bool>();
        else throw std::invalid_argument("unknown option '" + key + "'");
    }
    if (options.proxies > 1000000) throw std::invalid_argument("proxies must be at most 1000000");
    return options;
}

}  // namespace

// One mesh and, once started, one approximation of it.
class Session {
public:
    val load(const val& bytes, const std::string& name) {
        return guarded([&] {
            const std::vector<std::uint8_t> data = emscripten::convertJSArrayToNumberVector<std::uint8_t>(bytes);
            return set_mesh(read_mesh(name, data.data(), data.size()));
        });
    }

    val load_example(const std::string& name) {
        return guarded([&] { return set_mesh(example_mesh(name)); });
    }

    void start(const val& options) {
        guarded([&] {
            if (!mesh_) throw std::invalid_argument("load a mesh first");
            engine_.reset();
            engine_ = std::make_unique<Engine>(*mesh_, parse_options(options));
            return 0;
        });
    }

    // Steps for about `milliseconds` (at least one step); false when done. Also returns
    // when the Lloyd stage ends, so that callers can time it.
    bool step_for(double milliseconds) {
        return guarded([&] {
            Engine& e = engine();
            const bool was_lloyd = !e.lloyd_done();
            const double until = emscripten_get_now() + milliseconds;
            bool more = e.step();
            while (more && emscripten_get_now() < until && !e.lloyd_done() == was_lloyd) more = e.step();
            return more;
        });
    }

    void cancel() {
        guarded([&] {
            engine().cancel();
            engine().step();
            return 0;
        });
    }

    val progress() const {
        return guarded([&] {
            const Engine& e = engine();
            val p = val::object();
            p.set("phase", std::string(phase_name(e.last_phase())));
            p.set("proxies", static_cast<int>(e.proxies().size()));
            p.set("iteration", e.iterations());
            p.set("rms", e.rms());
            p.set("lloydDone", e.lloyd_done());
            p.set("done", e.done());
            p.set("stopReason", std::string(stop_reason_name(e.stop_reason())));
            return p;
        });
    }

    val face_labels() const { return guarded([&] { return copy_to_js("Int32Array", engine().face_labels()); }); }
    val lloyd_face_labels() const {
        return guarded([&] { return copy_to_js("Int32Array", engine().lloyd_face_labels()); });
    }
    val labels() const { return guarded([&] { return copy_to_js("Int32Array", engine().labels()); }); }

    val positions() const {
        return guarded([&] {
            std::vector<float> xyz;
            for (const Vec3& p : mesh().vertices) xyz.insert(xyz.end(), {float(p.x()), float(p.y()), float(p.z())});
            return copy_to_js("Float32Array", xyz);
        });
    }
    val triangles() const {
        return guarded([&] {
            std::vector<std::uint32_t> t;
            for (const Triangle& tri : mesh().triangles) t.insert(t.end(), {std::uint32_t(tri[0]), std::uint32_t(tri[1]), std::uint32_t(tri[2])});
            return copy_to_js("Uint32Array", t);
        });
    }
    val source_faces() const { return guarded([&] { return copy_to_js("Int32Array", mesh().source_face); }); }

    val projected() const {
        return guarded([&] {
            std::vector<float> xyz;
            for (const Vec3& p : engine().projected_vertices()) xyz.insert(xyz.end(), {float(p.x()), float(p.y()), float(p.z())});
            return copy_to_js("Float32Array", xyz);
        });
    }
    val vertex_errors() const {
        return guarded([&] {
            const auto& m = engine().metrics();
            std::vector<float> d;
            if (m) d.assign(m->vertex_distance.begin(), m->vertex_distance.end());
            return copy_to_js("Float32Array", d);
        });
    }

    std::string report(double load, double lloyd, double postprocess, double total) const {
        return guarded([&] { return make_report(mesh(), engine(), {load, lloyd, postprocess, total}).dump(); });
    }
    std::string proxies() const {
        return guarded([&] {
            nlohmann::json list = nlohmann::json::array();
            for (int i = 0; i < static_cast<int>(engine().proxies().size()); ++i) list.push_back(proxy_report(engine(), i));
            return list.dump();
        });
    }
    val glb() const { return guarded([&] { return bytes_to_js(export_glb(mesh(), engine())); }); }
    val projected_file(const std::string& name) const {
        return guarded([&] {
            const std::vector<Vec3> projected = engine().projected_vertices();
            if (projected.empty()) throw std::invalid_argument("no projected mesh (projection was off or cancelled)");
            return bytes_to_js(write_mesh(name, projected, mesh().triangles));
        });
    }

private:
    val set_mesh(Mesh mesh) {
        engine_.reset();
        mesh_ = std::make_unique<Mesh>(std::move(mesh));
        val info = val::object();
        info.set("vertices", mesh_->input_vertex_count);
        info.set("faces", mesh_->input_face_count);
        info.set("facesUsed", static_cast<int>(mesh_->triangles.size()));
        info.set("bboxDiagonal", bounding_box(*mesh_).diagonal());
        return info;
    }
    const Mesh& mesh() const {
        if (!mesh_) throw std::invalid_argument("load a mesh first");
        return *mesh_;
    }
    Engine& engine() const {
        if (!engine_) throw std::invalid_argument("start an approximation first");
        return *engine_;
    }

    std::unique_ptr<Mesh> mesh_;
    std::unique_ptr<Engine> engine_;
};

EMSCRIPTEN_BINDINGS(vqsa) {
    emscripten::class_<Session>("Session")
        .constructor<>()
        .function("load", &Session::load)
        .function("loadExample", &Session::load_example)
        .function("start", &Session::start)
        .function("stepFor", &Session::step_for)
        .function("cancel", &Session::cancel)
        .function("progress", &Session::progress)
        .function("faceLabels", &Session::face_labels)
        .function("lloydFaceLabels", &Session::lloyd_face_labels)
        .function("labels", &Session::labels)
        .function("positions", &Session::positions)
        .function("triangles", &Session::triangles)
        .function("sourceFaces", &Session::source_faces)
        .function("projected", &Session::projected)
        .function("vertexErrors", &Session::vertex_errors)
        .function("report", &Session::report)
        .function("proxies", &Session::proxies)
        .function("glb", &Session::glb)
        .function("projectedFile", &Session::projected_file);
    emscripten::function("exampleNames", emscripten::optional_override([] {
                             std::string names;
                             for (const char* n : example_names()) names += std::string(names.empty() ? "" : ",") + n;
                             return names;
                         }));
    emscripten::function("legend", emscripten::optional_override([] {
                             nlohmann::json legend = nlohmann::json::object();
                             for (int t = 0; t <= static_cast<int>(QuadricType::parallel_planes); ++t) {
                                 const Vec3 c = type_color(static_cast<QuadricType>(t));
                                 legend[type_name(static_cast<QuadricType>(t))] = {c.x(), c.y(), c.z()};
                             }
                             return legend.dump();
                         }));
    emscripten::function("version", emscripten::optional_override([] { return std::string(VQSA_VERSION); }));
}

}  // namespace vqsa
