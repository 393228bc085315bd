// The run report: what evaluation tools, the CLI and the browser read (JSON).
#pragma once

#include "lloyd/engine.h"

#include <nlohmann/json.hpp>

namespace vqsa {

struct Timing {
    double load = 0, lloyd = 0, postprocess = 0, total = 0;
};

// Everything in the input's coordinates and units.
nlohmann::json make_report(const Mesh& mesh, const Engine& engine, const Timing& timing);

// One proxy: id, type, coefficients, faces, area, rms_error, params (and metrics).
nlohmann::json proxy_report(const Engine& engine, int proxy);

// The parts of the report that describe the run, without per-face data: generator,
// version, input, options, stop_reason, iterations, rms_error, metrics.
nlohmann::json run_report(const Mesh& mesh, const Engine& engine);

}  // namespace vqsa
