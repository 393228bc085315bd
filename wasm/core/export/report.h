// The run report: what evaluation tools, the CLI and the browser read (JSON).
#pragma once

#include "pipeline/result.h"

#include <nlohmann/json.hpp>

namespace vqsa {

// Everything in the input's coordinates and units.
nlohmann::json make_report(const Result& result);

// One proxy: id, type, coefficients, faces, area, rms_error, params, locked, imposed_type
// (and metrics).
nlohmann::json proxy_report(const Result& result, int proxy);

// The parts of the report that describe the run, without per-face data: generator,
// version, input, options, stop_reason, iterations, rms_error, edits, metrics.
nlohmann::json run_report(const Result& result);

}  // namespace vqsa
