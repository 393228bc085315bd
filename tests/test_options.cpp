// The option schema (pipeline/options.h): one description every front end is made from.
#include "pipeline/options.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <set>

using namespace vqsa;
using nlohmann::json;

using test::invalid_argument_of;

TEST(Options, EveryDefaultIsValidAndNamesAreUnique) {
    const Options defaults;
    EXPECT_NO_THROW(validate(defaults));
    std::set<std::string> names;
    for (const OptionSpec& spec : option_schema()) {
        EXPECT_TRUE(names.insert(spec.name).second) << spec.name;
        EXPECT_FALSE(spec.help.empty()) << spec.name;
        // Setting each option to its own default leaves the options unchanged.
        Options o;
        set_option(o, spec.name, spec.get(defaults));
        EXPECT_EQ(options_to_json(o), options_to_json(defaults)) << spec.name;
    }
    const json schema = schema_to_json();
    ASSERT_EQ(schema.size(), option_schema().size());
    EXPECT_EQ(schema[0]["name"], "proxies");
    EXPECT_EQ(schema[0]["default"], "auto");
    // A boolean's words (what <vqsa-viewer> turns attributes into) are what the core reads.
    for (const json& entry : schema) {
        if (entry["kind"] != "boolean") continue;
        ASSERT_EQ(entry["words"].size(), 8u) << entry["name"];
        for (const auto& [word, meaning] : entry["words"].items()) {
            Options o;
            set_option(o, entry["name"].get<std::string>(), word);
            EXPECT_EQ(options_to_json(o)[entry["name"].get<std::string>()], meaning) << word;
        }
    }
}

TEST(Options, NamesAndValuesAsFrontEndsSendThem) {
    EXPECT_EQ(camel_case("max-iterations"), "maxIterations");
    EXPECT_EQ(camel_case("crease-angle"), "creaseAngle");
    Options o;
    set_option(o, "max-iterations", "12");           // a command-line word
    set_option(o, "creaseAngle", 30);                 // JavaScript
    set_option(o, "smooth", "off");                   // an attribute
    set_option(o, "init", "paper");
    set_option(o, "proxies", "auto");
    EXPECT_EQ(o.lloyd.max_iterations, 12);
    EXPECT_EQ(o.lloyd.features.crease_angle, 30);
    EXPECT_FALSE(o.smooth);
    EXPECT_EQ(o.lloyd.init, Initialization::paper);
    EXPECT_EQ(o.lloyd.proxies, 0);
    // Round trip through JSON.
    const Options back = options_from_json(options_to_json(o));
    EXPECT_EQ(options_to_json(back), options_to_json(o));
}

TEST(Options, BadValuesSayWhichOptionAndWhatItTakes) {
    Options o;
    EXPECT_EQ(invalid_argument_of([&] { set_option(o, "proxies", 0); }), "proxies must be an integer between 1 and 1000000 or 'auto', not 0");
    EXPECT_EQ(invalid_argument_of([&] { set_option(o, "proxies", 1e6 + 1); }),
              "proxies must be an integer between 1 and 1000000 or 'auto', not 1000001.0");
    EXPECT_EQ(invalid_argument_of([&] { set_option(o, "rings", "2.5"); }), "rings must be an integer between 1 and 100, not \"2.5\"");
    EXPECT_EQ(invalid_argument_of([&] { set_option(o, "tolerance", -1); }), "tolerance must be a number between 0 and 1, not -1");
    // The seed's bound, the largest integer a JavaScript number holds, in full (it read 9.007199254740991e+15).
    EXPECT_EQ(invalid_argument_of([&] { set_option(o, "seed", -1); }),
              "seed must be an integer between 0 and 9007199254740991, not -1");
    EXPECT_EQ(invalid_argument_of([&] { set_option(o, "init", "random"); }), "init must be one of 'features' 'paper', not \"random\"");
    EXPECT_EQ(invalid_argument_of([&] { set_option(o, "smooth", "maybe"); }), "smooth must be true or false, not \"maybe\"");
    EXPECT_EQ(invalid_argument_of([&] { set_option(o, "speed", 1); }), "unknown option 'speed'");
    EXPECT_EQ(invalid_argument_of([&] { options_from_json(json::array()); }), "options must be an object");
    // Values set on the struct directly meet the same checks.
    o.smoothing.lambda = -2;
    EXPECT_EQ(invalid_argument_of([&] { validate(o); }), "lambda must be a number between 0 and 1000000, not -2.0");
}
