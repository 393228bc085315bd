// The pipeline for JavaScript (embind): typed arrays in and out, no per-element calls,
// and every C++ exception turned into a JS Error carrying its message.
#include "examples.h"
#include "export/gltf_export.h"
#include "export/palette.h"
#include "export/report.h"
#include "io/mesh_io.h"
#include "io/mesh_write.h"
#include "pipeline/pipeline.h"

#include <emscripten/bind.h>
#include <emscripten/emscripten.h>
#include <emscripten/val.h>

#include <cstring>
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

}  // namespace

// One mesh and, once started, one approximation of it.
class Session {
public:
    val load(const val& bytes, const std::string& name) {
        return guarded([&] {
            const double start = emscripten_get_now();
            const std::vector<std::uint8_t> data = emscripten::convertJSArrayToNumberVector<std::uint8_t>(bytes);
            return set_mesh(read_mesh(name, data.data(), data.size()), start);
        });
    }

    val load_example(const std::string& name) {
        return guarded([&] { return set_mesh(example_mesh(name), emscripten_get_now()); });
    }

    // `options`: the option schema's camelCase names (optionSchema()); numbers may
    // also come as strings, as HTML attributes give them.
    void start(const val& options) {
        guarded([&] {
            if (!mesh_) throw std::invalid_argument("load a mesh first");
            pipeline_.reset();
            result_.reset();
            const std::string text = val::global("JSON").call<std::string>("stringify", options);
            nlohmann::json object;
            try {
                object = nlohmann::json::parse(text);
            } catch (const nlohmann::json::exception&) {
                throw std::invalid_argument("options must be a plain object");
            }
            pipeline_ = std::make_unique<Pipeline>(*mesh_, model_, options_from_json(object));
            return 0;
        });
    }

    // Steps for about `milliseconds` (at least one step), or up to a Lloyd operation
    // (insert, split, merge, teleport) or a new stage, so that the page sees every proxy
    // count and every stage the run passes through (and can cancel in each); false when done.
    bool step_for(double milliseconds) {
        return guarded([&] {
            Pipeline& p = pipeline();
            const double until = emscripten_get_now() + milliseconds;
            const Stage stage = p.progress().stage;
            auto boundary = [&] {
                const Progress now = p.progress();
                return now.stage != stage || (now.stage == Stage::lloyd && std::strcmp(now.phase, "lloyd") != 0);
            };
            bool more = p.step();
            while (more && !boundary() && emscripten_get_now() < until) more = p.step();
            return more;
        });
    }

    // Starts an edit of the finished result, `edit` as JSON text (docs/EDITS.md); stepFor
    // carries it out like a run, cancel drops it.
    void edit(const std::string& edit) {
        guarded([&] {
            nlohmann::json object;
            try {
                object = nlohmann::json::parse(edit);
            } catch (const nlohmann::json::exception&) {
                throw std::invalid_argument("an edit must be a JSON object");
            }
            pipeline().edit(edit_from_json(object));
            result_.reset();
            return 0;
        });
    }
    // Back to the result before the last edit (forward again); false when there is none.
    bool undo() { return guarded([&] { return history_step(pipeline().undo()); }); }
    bool redo() { return guarded([&] { return history_step(pipeline().redo()); }); }
    val history() const {
        return guarded([&] {
            val out = val::object();
            out.set("canUndo", pipeline().can_undo());
            out.set("canRedo", pipeline().can_redo());
            return out;
        });
    }

    void cancel() {
        guarded([&] {
            pipeline().cancel();
            pipeline().step();
            return 0;
        });
    }

    val progress() const {
        return guarded([&] {
            const Pipeline& p = pipeline();
            const Progress now = p.progress();
            val out = val::object();
            out.set("stage", std::string(stage_name(now.stage)));
            out.set("phase", std::string(now.phase));
            out.set("proxies", now.proxies);
            out.set("iteration", now.iterations);
            out.set("rms", now.rms);
            out.set("settledProxies", now.settled_proxies);
            out.set("settledRms", now.settled_rms);
            out.set("fraction", now.fraction);
            out.set("done", p.done());
            return out;
        });
    }

    // The current region of every kept face (live during the run).
    val face_labels() const { return guarded([&] { return copy_to_js("Int32Array", pipeline().face_labels()); }); }

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

    // The result of a finished run.
    val lloyd_face_labels() const { return guarded([&] { return copy_to_js("Int32Array", result().lloyd_face_labels); }); }
    val labels() const { return guarded([&] { return copy_to_js("Int32Array", result().labels); }); }
    val projected() const {
        return guarded([&] {
            std::vector<float> xyz;
            for (const Vec3& p : result().projected) xyz.insert(xyz.end(), {float(p.x()), float(p.y()), float(p.z())});
            return copy_to_js("Float32Array", xyz);
        });
    }
    val vertex_errors() const {
        return guarded([&] {
            const auto& m = result().metrics;
            std::vector<float> d;
            if (m) d.assign(m->vertex_distance.begin(), m->vertex_distance.end());
            return copy_to_js("Float32Array", d);
        });
    }
    std::string report() const { return guarded([&] { return make_report(result()).dump(); }); }
    std::string proxies() const {
        return guarded([&] {
            nlohmann::json list = nlohmann::json::array();
            for (int i = 0; i < static_cast<int>(result().proxies.size()); ++i) list.push_back(proxy_report(result(), i));
            return list.dump();
        });
    }
    // `colours`: "region" or "type".
    val glb(const std::string& colours) const {
        return guarded([&] { return bytes_to_js(export_glb(mesh(), result(), glb_colours_from(colours))); });
    }
    val projected_file(const std::string& name) const {
        return guarded([&] {
            if (result().projected.empty()) throw std::invalid_argument("no projected mesh (projection was off or cancelled)");
            return bytes_to_js(write_mesh(name, result().projected, mesh().triangles));
        });
    }

private:
    bool history_step(bool moved) {
        if (moved) result_.reset();
        return moved;
    }
    val set_mesh(Mesh mesh, double started) {
        pipeline_.reset();
        result_.reset();
        model_.reset();
        mesh_.reset();
        // Built once per mesh: every run on it shares the model, and starting one is quick.
        // Nothing is kept when it fails (out of memory): the session has no mesh then.
        std::shared_ptr<const Model> model;
        if (!mesh.triangles.empty()) model = std::make_shared<const Model>(make_model(mesh));
        mesh_ = std::make_unique<Mesh>(std::move(mesh));
        model_ = std::move(model);
        load_seconds_ = (emscripten_get_now() - started) / 1000;
        val info = val::object();
        info.set("vertices", mesh_->input_vertex_count);
        info.set("faces", mesh_->input_face_count);
        info.set("facesUsed", static_cast<int>(mesh_->triangles.size()));
        info.set("bboxDiagonal", bounding_box(*mesh_).diagonal());
        info.set("loadSeconds", load_seconds_);
        return info;
    }
    const Mesh& mesh() const {
        if (!mesh_) throw std::invalid_argument("load a mesh first");
        return *mesh_;
    }
    Pipeline& pipeline() const {
        if (!pipeline_) throw std::invalid_argument("start an approximation first");
        return *pipeline_;
    }
    const Result& result() const {
        if (!pipeline().done()) throw std::invalid_argument("the approximation has not finished");
        if (!result_) result_ = std::make_unique<Result>(pipeline().result(load_seconds_));
        return *result_;
    }

    std::unique_ptr<Mesh> mesh_;
    std::shared_ptr<const Model> model_;
    std::unique_ptr<Pipeline> pipeline_;
    mutable std::unique_ptr<Result> result_;
    double load_seconds_ = 0;  // reading and cleaning the mesh, building its model
};

EMSCRIPTEN_BINDINGS(vqsa) {
    emscripten::class_<Session>("Session")
        .constructor<>()
        .function("load", &Session::load)
        .function("loadExample", &Session::load_example)
        .function("start", &Session::start)
        .function("stepFor", &Session::step_for)
        .function("cancel", &Session::cancel)
        .function("edit", &Session::edit)
        .function("undo", &Session::undo)
        .function("redo", &Session::redo)
        .function("history", &Session::history)
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
                             for (const std::string& n : example_names()) names += std::string(names.empty() ? "" : ",") + n;
                             return names;
                         }));
    emscripten::function("palette", emscripten::optional_override([] { return palette_json().dump(); }));
    emscripten::function("optionSchema", emscripten::optional_override([] { return schema_to_json().dump(); }));
    emscripten::function("version", emscripten::optional_override([] { return std::string(VQSA_VERSION); }));
}

}  // namespace vqsa
