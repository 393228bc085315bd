// Every option of a run, and the one schema the CLI, the WASM bindings, the app's controls
// and the custom element's attributes are made from.
#pragma once

#include "lloyd/lloyd.h"
#include "post/graph_cut.h"
#include "post/metrics.h"

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace vqsa {

struct Options {
    LloydOptions lloyd;
    bool smooth = true;
    SmoothingOptions smoothing;
    bool refit = true;  // select each region's type among the candidates (fitting/model_selection.h)
    bool project = true;
    // Foot points farther than this (relative to the longest bounding-box side) are
    // taken for stray roots and ignored.
    double max_projection_distance = 0.05;
    bool measure = true;  // needs `project`
    MetricsOptions metrics;
};

enum class OptionKind {
    count,    // a positive integer, or "auto"
    integer,
    number,
    boolean,
    choice,
};

// One user-facing option. `name` is kebab-case: the CLI flag (--name, or --no-name for a
// boolean that defaults to true), the element's attribute, the report's key; JavaScript
// uses its camelCase form.
struct OptionSpec {
    std::string name;
    OptionKind kind;
    double min = 0, max = 0;           // count, integer, number
    std::vector<std::string> choices;  // choice
    std::string help;
    void (*set)(Options&, const nlohmann::json& value);  // value already checked and normalised
    nlohmann::json (*get)(const Options&);
    // A number whose 0 turns the option off: a typical value to turn it on with (front
    // ends show such an option as a switch and a field). 0 for every other option.
    double typical_when_on = 0;
};

const std::vector<OptionSpec>& option_schema();

// kebab-case → camelCase ("max-iterations" → "maxIterations").
std::string camel_case(std::string_view name);

// Sets one option by its kebab- or camelCase name from a JSON value or from text (a
// command-line word, an attribute): numbers may come as strings, booleans as
// true/false/1/0. Throws std::invalid_argument saying which option and what it takes.
void set_option(Options& options, std::string_view name, const nlohmann::json& value);
// Every key of a JSON object, as set_option.
Options options_from_json(const nlohmann::json& object, Options options = {});

// The user-facing options as a JSON object (kebab-case keys; proxies may be "auto").
nlohmann::json options_to_json(const Options& options);
// The schema for front ends: name, js, kind, default, min, max, choices, help.
nlohmann::json schema_to_json();

// Throws std::invalid_argument when the options do not make sense together.
void validate(const Options& options);

}  // namespace vqsa
