// The tokenizer of the text formats (io/text_tokenizer.h): tokens, lines, comments,
// numbers, and the errors that name the line.
#include "io/text_tokenizer.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

using namespace vqsa;

using test::invalid_argument_of;

TEST(TextTokenizer, TokensLinesAndComments) {
    TextTokenizer t("OFF # a comment\n\t3 1 0\r\n# only a comment\n0.5 -1e-3 +2\n");
    EXPECT_EQ(t.token("a header"), "OFF");
    EXPECT_EQ(t.line(), 1u);
    EXPECT_EQ(t.token_on_line(), "");  // the rest of line 1 is a comment
    EXPECT_EQ(t.integer("a count"), 3);
    EXPECT_EQ(t.line(), 2u);
    EXPECT_EQ(t.token_on_line(), "1");
    EXPECT_EQ(t.token_on_line(), "0");
    EXPECT_EQ(t.token_on_line(), "");   // "\r\n" ends the line
    const Vec3 p = t.point();
    EXPECT_EQ(t.line(), 4u);            // the comment line was skipped and counted
    EXPECT_EQ(p, Vec3(0.5, -1e-3, 2));
    EXPECT_TRUE(t.at_end());
}

TEST(TextTokenizer, NoCommentCharacterAndSkipLine) {
    TextTokenizer t("a#b c\nd", '\0');
    EXPECT_EQ(t.token("x"), "a#b");
    t.skip_line();
    EXPECT_EQ(t.token("x"), "d");
    EXPECT_EQ(t.line(), 2u);
}

TEST(TextTokenizer, ErrorsNameTheLineAndWhatWasExpected) {
    EXPECT_EQ(invalid_argument_of([] { TextTokenizer t("1 2\n3 x"); t.point(); t.number("a vertex coordinate"); }),
              "line 2: expected a vertex coordinate, found 'x'");
    EXPECT_EQ(invalid_argument_of([] { TextTokenizer t("\n\n7"); t.integer("a count"); t.integer("a face index"); }),
              "line 3: unexpected end of file, expected a face index");
    EXPECT_EQ(invalid_argument_of([] { TextTokenizer t("1.5"); t.integer("a count"); }), "line 1: expected a count, found '1.5'");
}

TEST(TextTokenizer, NumbersMustBeWholeTokens) {
    double d;
    std::int64_t i;
    EXPECT_TRUE(parse_double("-1.25e2", d));
    EXPECT_EQ(d, -125);
    EXPECT_FALSE(parse_double("1.0f", d));
    EXPECT_FALSE(parse_double("", d));
    // Every digit counts, however many: a prefix that parses is no number.
    EXPECT_TRUE(parse_double(std::string(100, '1'), d));
    EXPECT_EQ(d, 1.1111111111111111e99);
    EXPECT_FALSE(parse_double(std::string(100, '1') + "x", d));
    // strtod's forms that files carry: a leading '+', either exponent sign, inf.
    EXPECT_TRUE(parse_double("+0.5e+1", d));
    EXPECT_EQ(d, 5);
    EXPECT_FALSE(parse_double("+-1", d));
    EXPECT_FALSE(parse_double("+", d));
    EXPECT_TRUE(parse_double("-inf", d));
    EXPECT_TRUE(std::isinf(d));
    // Rounded correctly, as strtod does: halfway between two doubles, to the even one.
    EXPECT_TRUE(parse_double("9007199254740993", d));
    EXPECT_EQ(d, 9007199254740992.0);
    EXPECT_TRUE(parse_double("0.1", d));
    EXPECT_EQ(d, std::strtod("0.1", nullptr));
    // A NUL byte inside a token ends no token and makes no number (a fuzzer finding).
    EXPECT_FALSE(parse_double(std::string("1\0" "2", 3), d));
    EXPECT_TRUE(parse_integer("-42", i));
    EXPECT_EQ(i, -42);
    EXPECT_FALSE(parse_integer("99999999999999999999", i));  // overflow
    EXPECT_FALSE(parse_integer("4.0", i));
    const std::string text("v 1\0 2", 6);  // outlives the tokenizer, which only views it
    TextTokenizer t(text);
    EXPECT_EQ(t.token("x"), "v");
    EXPECT_EQ(t.token("x"), std::string_view("1\0", 2));
}
