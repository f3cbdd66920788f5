#include "scene/sdl_lexer.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "util/error.h"

namespace vkray {
namespace {

std::vector<std::string> texts(const std::vector<Token>& tokens) {
    std::vector<std::string> out;
    for (const Token& t : tokens) out.push_back(t.text);
    return out;
}

// All tokens of a stream after def/use substitution.
std::vector<Token> drain(SdlTokenStream& stream) {
    std::vector<Token> out;
    while (std::optional<Token> t = stream.next()) out.push_back(*t);
    return out;
}

std::vector<Token> expand(const std::string& text, const SdlOptions& options = {}) {
    SdlTokenStream stream(tokenizeSdl(text, "t.sdl"), options);
    return drain(stream);
}

std::string errorOf(const std::string& text, const SdlOptions& options = {}) {
    try {
        expand(text, options);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(SdlLexer, SplitsOnAnyWhiteSpace) {
    const auto tokens = tokenizeSdl("light  1\t2\n3 \r\n\v\f4", "t.sdl");
    EXPECT_EQ(texts(tokens), (std::vector<std::string>{"light", "1", "2", "3", "4"}));
}

TEST(SdlLexer, BracesAreTokensEvenGluedToWords) {
    EXPECT_EQ(texts(tokenizeSdl("}def jackPart{ a{b}c {{}}", "t.sdl")),
              (std::vector<std::string>{"}", "def", "jackPart", "{", "a", "{", "b", "}", "c", "{",
                                        "{", "}", "}"}));
}

TEST(SdlLexer, CommentsRunToTheEndOfTheLine) {
    EXPECT_EQ(texts(tokenizeSdl("! whole line\nsphere ! tail { } words\ncube!glued\n!", "t.sdl")),
              (std::vector<std::string>{"sphere", "cube"}));
}

TEST(SdlLexer, DotsAndDigitsStayInOneWord) {
    EXPECT_EQ(texts(tokenizeSdl("mesh pawn.3vn extrude hlArch.dat", "t.sdl")),
              (std::vector<std::string>{"mesh", "pawn.3vn", "extrude", "hlArch.dat"}));
}

TEST(SdlLexer, LocationsAreLineAndByteColumn) {
    const auto tokens = tokenizeSdl("light 1\n\tpush  }pop\n", "t.sdl");
    ASSERT_EQ(tokens.size(), 5u);
    EXPECT_EQ(tokens[0].loc.str(), "t.sdl:1:1");
    EXPECT_EQ(tokens[1].loc.str(), "t.sdl:1:7");
    EXPECT_EQ(tokens[2].loc.str(), "t.sdl:2:2");  // a tab is one byte
    EXPECT_EQ(tokens[3].loc.str(), "t.sdl:2:8");
    EXPECT_EQ(tokens[4].loc.str(), "t.sdl:2:9");
    // One file name shared by every token; no expansion on file tokens.
    EXPECT_EQ(tokens[0].loc.file.get(), tokens[4].loc.file.get());
    EXPECT_EQ(tokens[0].expansion, nullptr);
}

TEST(SdlLexer, CrlfAndLatin1CommentsAreFine) {
    const std::string text = "! \x96 Latin-1 dash\r\nlight 1 2 3\r\n  sphere\r\n";
    const auto tokens = tokenizeSdl(text, "t.sdl");
    EXPECT_EQ(texts(tokens), (std::vector<std::string>{"light", "1", "2", "3", "sphere"}));
    EXPECT_EQ(tokens[3].loc.str(), "t.sdl:2:11");
    EXPECT_EQ(tokens[4].loc.str(), "t.sdl:3:3");
}

TEST(SdlLexer, EmptyAndCommentOnlyTextHasNoTokens) {
    EXPECT_TRUE(tokenizeSdl("", "t.sdl").empty());
    EXPECT_TRUE(tokenizeSdl("  \n! nothing", "t.sdl").empty());
}

TEST(SdlNumber, AcceptsTheFormsRealFilesUse) {
    const std::pair<const char*, double> good[] = {
        {"1", 1},       {"-2", -2}, {"+3", 3},     {".7", 0.7},      {"-.5", -0.5},
        {"+.25", 0.25}, {"1.", 1},  {"1e3", 1000}, {"2.5E-1", 0.25}, {"-4.75071e-009", -4.75071e-9},
    };
    for (const auto& [text, expected] : good) {
        double value = -999;
        EXPECT_EQ(parseSdlNumber(text, value), NumberStatus::Ok) << text;
        EXPECT_EQ(value, expected) << text;
    }
}

TEST(SdlNumber, RefusesMalformedNonFiniteAndOutOfRange) {
    for (const char* text : {"1.2.3", "abc", "", "+", "-", "+-1", "1,5", "0x10", "1e", "3x", "."})
        EXPECT_EQ(
            [&] {
                double v = 0;
                return parseSdlNumber(text, v);
            }(),
            NumberStatus::Malformed)
            << text;
    for (const char* text : {"nan", "NaN", "-nan", "inf", "-inf", "infinity"})
        EXPECT_EQ(
            [&] {
                double v = 0;
                return parseSdlNumber(text, v);
            }(),
            NumberStatus::NotFinite)
            << text;
    for (const char* text : {"1e999", "-1e999"})
        EXPECT_EQ(
            [&] {
                double v = 0;
                return parseSdlNumber(text, v);
            }(),
            NumberStatus::OutOfRange)
            << text;
}

TEST(SdlTokenStream, DefIsTakenOutAndUsePastesItsTokens) {
    const auto tokens = expand("def two { 1 2 }\nlight use two 3\nuse two");
    EXPECT_EQ(texts(tokens), (std::vector<std::string>{"light", "1", "2", "3", "1", "2"}));
    // Pasted tokens keep the place they were written and name the use.
    EXPECT_EQ(tokens[1].loc.str(), "t.sdl:1:11");
    ASSERT_NE(tokens[1].expansion, nullptr);
    EXPECT_EQ(tokens[1].expansion->name, "two");
    EXPECT_EQ(tokens[1].expansion->useLoc.str(), "t.sdl:2:7");
    EXPECT_EQ(tokens[1].expansion->parent, nullptr);
    EXPECT_EQ(tokens[3].expansion, nullptr);
    EXPECT_EQ(tokens[4].expansion->useLoc.str(), "t.sdl:3:1");
}

TEST(SdlTokenStream, NestedUsesChainTheirExpansions) {
    const auto tokens = expand("def inner { x }\ndef outer { use inner }\nuse outer");
    ASSERT_EQ(texts(tokens), (std::vector<std::string>{"x"}));
    const Expansion* e = tokens[0].expansion.get();
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->name, "inner");
    EXPECT_EQ(e->useLoc.str(), "t.sdl:2:13");
    ASSERT_NE(e->parent, nullptr);
    EXPECT_EQ(e->parent->name, "outer");
    EXPECT_EQ(e->parent->useLoc.str(), "t.sdl:3:1");
}

TEST(SdlTokenStream, NestedBracesStayInTheBody) {
    EXPECT_EQ(texts(expand("def a { { b } c }use a")),
              (std::vector<std::string>{"{", "b", "}", "c"}));
}

TEST(SdlTokenStream, BodyIsStoredUncheckedAndLaterDefWins) {
    EXPECT_EQ(texts(expand("def a { 1.2.3 use nothing } def a { ok } use a")),
              (std::vector<std::string>{"ok"}));
}

TEST(SdlTokenStream, PeekDoesNotConsume) {
    SdlTokenStream stream(tokenizeSdl("def a { x } use a y", "t.sdl"), {});
    ASSERT_NE(stream.peek(), nullptr);
    EXPECT_EQ(stream.peek()->text, "x");
    EXPECT_EQ(stream.next()->text, "x");
    EXPECT_EQ(stream.next()->text, "y");
    EXPECT_EQ(stream.peek(), nullptr);
    EXPECT_FALSE(stream.next().has_value());
}

TEST(SdlTokenStream, UseAtTheEndOfABodyIsNotRecursion) {
    // The same def pasted again after its paste has finished is fine.
    EXPECT_EQ(texts(expand("def a { x } def b { use a use a } use b use b")).size(), 4u);
}

TEST(SdlTokenStream, ErrorsNameThePlace) {
    EXPECT_NE(errorOf("def a { x").find("t.sdl:1:7: error: '{' is never closed"),
              std::string::npos);
    EXPECT_NE(errorOf("def a { { x } y").find("t.sdl:1:7: error: '{' is never closed"),
              std::string::npos);
    EXPECT_NE(errorOf("def a { { x").find("t.sdl:1:9: error: '{' is never closed"),
              std::string::npos);
    EXPECT_NE(errorOf("x\nuse b").find("t.sdl:2:1: error: 'use b': no def named 'b'"),
              std::string::npos);
    EXPECT_NE(errorOf("def").find("t.sdl:1:1: error: 'def' is missing its name"),
              std::string::npos);
    EXPECT_NE(errorOf("def a b").find("t.sdl:1:7: error: expected '{'"), std::string::npos);
    EXPECT_NE(errorOf("x use").find("t.sdl:1:3: error: 'use' is missing"), std::string::npos);
}

TEST(SdlTokenStream, RecursionIsCaughtEvenInTailPosition) {
    const std::string direct = errorOf("def a { x use a }\nuse a");
    EXPECT_NE(direct.find("t.sdl:1:11: error: recursive 'use a' (a -> a)"), std::string::npos)
        << direct;
    EXPECT_NE(direct.find("t.sdl:2:1: note: in text pasted by 'use a'"), std::string::npos);
    const std::string indirect = errorOf("def a { use b }\ndef b { use a }\nuse a");
    EXPECT_NE(indirect.find("t.sdl:2:9: error: recursive 'use a' (a -> b -> a)"), std::string::npos)
        << indirect;
}

TEST(SdlTokenStream, ExpansionLimitsStopExponentialPasting) {
    std::string text = "def a0 { x }\n";
    for (int i = 1; i <= 40; ++i)
        text += "def a" + std::to_string(i) + " { use a" + std::to_string(i - 1) + " use a" +
                std::to_string(i - 1) + " }\n";
    text += "use a40\n";
    SdlOptions small;
    small.maxExpandedTokens = 1000;
    const std::string message = errorOf(text, small);
    EXPECT_NE(message.find("would paste more than 1000 tokens"), std::string::npos) << message;

    SdlOptions shallow;
    shallow.maxUseDepth = 5;
    EXPECT_NE(errorOf(text, shallow).find("nested more than 5 uses deep"), std::string::npos);
    // Five levels are allowed, the sixth is not.
    EXPECT_NO_THROW(
        expand("def a0 { x } def a1 { use a0 } def a2 { use a1 } def a3 { use a2 }"
               " def a4 { use a3 } use a4",
               shallow));
}

TEST(SdlTokenStream, CountsWhatItPasted) {
    SdlTokenStream stream(tokenizeSdl("def a { 1 2 3 } use a use a", "t.sdl"), {});
    drain(stream);
    EXPECT_EQ(stream.expandedTokenCount(), 6u);
}

}  // namespace
}  // namespace vkray
