#include "scene/tokenizer.h"

#include <gtest/gtest.h>

#include <vector>

namespace prism {
namespace {

std::vector<Token> All(Tokenizer &tok) {
    std::vector<Token> out;
    while (true) {
        Token t = tok.Next();
        if (t.kind == TokenKind::End) break;
        out.push_back(t);
    }
    return out;
}

// Runs `text` through a tokenizer named "t.pbrt" and returns the SceneError it throws.
SceneError ErrorFor(const std::string &text) {
    Tokenizer tok(text, "t.pbrt");
    try {
        All(tok);
    } catch (const SceneError &e) {
        return e;
    }
    ADD_FAILURE() << "no error for: " << text;
    return SceneError("none");
}

TEST(Tokenizer, KindsTextAndLocations) {
    Tokenizer tok("Shape \"sphere\"\n  \"float radius\" [ 2.5 ]\n", "a.pbrt");
    auto ts = All(tok);
    ASSERT_EQ(ts.size(), 6u);
    EXPECT_EQ(ts[0].kind, TokenKind::Word);
    EXPECT_EQ(ts[0].text, "Shape");
    EXPECT_EQ(ts[0].Loc().ToString(), "a.pbrt:1:1");
    EXPECT_EQ(ts[1].kind, TokenKind::String);
    EXPECT_EQ(ts[1].text, "sphere");
    EXPECT_EQ(ts[1].Loc().ToString(), "a.pbrt:1:7");
    EXPECT_EQ(ts[2].kind, TokenKind::String);
    EXPECT_EQ(ts[2].Loc().ToString(), "a.pbrt:2:3");
    EXPECT_EQ(ts[3].kind, TokenKind::LBracket);
    EXPECT_EQ(ts[3].Loc().ToString(), "a.pbrt:2:18");
    EXPECT_EQ(ts[4].kind, TokenKind::Number);
    EXPECT_DOUBLE_EQ(ts[4].number, 2.5);
    EXPECT_EQ(ts[4].Loc().ToString(), "a.pbrt:2:20");
    EXPECT_EQ(ts[5].kind, TokenKind::RBracket);
    EXPECT_EQ(ts[5].Loc().ToString(), "a.pbrt:2:24");
}

TEST(Tokenizer, BracketsAreTokensEvenWhenGlued) {
    Tokenizer tok("[1 2][\"a\"]", "f");
    auto ts = All(tok);
    ASSERT_EQ(ts.size(), 7u);
    EXPECT_EQ(ts[0].kind, TokenKind::LBracket);
    EXPECT_EQ(ts[3].kind, TokenKind::RBracket);
    EXPECT_EQ(ts[4].kind, TokenKind::LBracket);
    EXPECT_EQ(ts[5].kind, TokenKind::String);
    EXPECT_EQ(ts[5].text, "a");
    EXPECT_EQ(ts[6].kind, TokenKind::RBracket);
    EXPECT_EQ(ts[6].column, 10);
}

TEST(Tokenizer, CommentsRunToEndOfLine) {
    Tokenizer tok("# header \"not a string\n Foo # trailing [ 1 2\n\t# only\nBar", "f");
    auto ts = All(tok);
    ASSERT_EQ(ts.size(), 2u);
    EXPECT_EQ(ts[0].text, "Foo");
    EXPECT_EQ(ts[0].line, 2);
    EXPECT_EQ(ts[0].column, 2);
    EXPECT_EQ(ts[1].text, "Bar");
    EXPECT_EQ(ts[1].line, 4);
    EXPECT_EQ(ts[1].column, 1);
}

TEST(Tokenizer, HashInsideStringIsNotAComment) {
    Tokenizer tok("\"a # b\" X", "f");
    auto ts = All(tok);
    ASSERT_EQ(ts.size(), 2u);
    EXPECT_EQ(Tokenizer::StringValue(ts[0]), "a # b");
}

TEST(Tokenizer, StringEscapes) {
    Tokenizer tok(R"("q\"uote" "back\\slash" "nl\n" "tab\t" "plain")", "f");
    auto ts = All(tok);
    ASSERT_EQ(ts.size(), 5u);
    EXPECT_EQ(Tokenizer::StringValue(ts[0]), "q\"uote");
    EXPECT_EQ(Tokenizer::StringValue(ts[1]), "back\\slash");
    EXPECT_EQ(Tokenizer::StringValue(ts[2]), "nl\n");
    EXPECT_EQ(Tokenizer::StringValue(ts[3]), "tab\t");
    EXPECT_EQ(Tokenizer::StringValue(ts[4]), "plain");
    EXPECT_FALSE(ts[4].hasEscapes);
    EXPECT_TRUE(ts[0].hasEscapes);
}

TEST(Tokenizer, Numbers) {
    Tokenizer tok("1 -2 +3 .5 -.25 1e-3 2.5E+2 0", "f");
    auto ts = All(tok);
    std::vector<double> expect = {1, -2, 3, 0.5, -0.25, 1e-3, 250, 0};
    ASSERT_EQ(ts.size(), expect.size());
    for (size_t i = 0; i < ts.size(); ++i) {
        EXPECT_EQ(ts[i].kind, TokenKind::Number) << i;
        EXPECT_DOUBLE_EQ(ts[i].number, expect[i]) << i;
    }
    EXPECT_EQ(ts[2].text, "+3");
}

TEST(Tokenizer, AnyWhitespaceSeparates) {
    Tokenizer tok("A\r\nB\tC\v\fD   E", "f");
    auto ts = All(tok);
    ASSERT_EQ(ts.size(), 5u);
    EXPECT_EQ(ts[1].text, "B");
    EXPECT_EQ(ts[1].line, 2);
    EXPECT_EQ(ts[4].text, "E");
}

TEST(Tokenizer, PeekDoesNotConsume) {
    Tokenizer tok("A B", "f");
    EXPECT_EQ(tok.Peek().text, "A");
    EXPECT_EQ(tok.Peek().text, "A");
    EXPECT_EQ(tok.Next().text, "A");
    EXPECT_EQ(tok.Next().text, "B");
    EXPECT_EQ(tok.Peek().kind, TokenKind::End);
    EXPECT_EQ(tok.Next().kind, TokenKind::End);
}

TEST(Tokenizer, UnterminatedString) {
    SceneError e = ErrorFor("Shape\n  \"sphere");
    EXPECT_EQ(e.Message(), "unterminated string");
    EXPECT_EQ(e.Loc().ToString(), "t.pbrt:2:3");
    EXPECT_EQ(std::string(e.what()), "t.pbrt:2:3: error: unterminated string");
    // A trailing backslash must not read past the end.
    EXPECT_EQ(ErrorFor("\"abc\\").Message(), "unterminated string");
}

TEST(Tokenizer, StringAcrossNewline) {
    SceneError e = ErrorFor("A \"two\nlines\"");
    EXPECT_EQ(e.Message(), "unterminated string (a newline inside quotes)");
    EXPECT_EQ(e.Loc().ToString(), "t.pbrt:1:3");
}

TEST(Tokenizer, UnknownCharacter) {
    SceneError e = ErrorFor("Shape @");
    EXPECT_EQ(e.Message(), "unexpected character '@'");
    EXPECT_EQ(e.Loc().ToString(), "t.pbrt:1:7");
    EXPECT_EQ(ErrorFor("{").Message(), "unexpected character '{'");
    EXPECT_EQ(ErrorFor("\x01").Message(), "unexpected character 0x01");
}

TEST(Tokenizer, InvalidNumbers) {
    EXPECT_EQ(ErrorFor("1.2.3").Message(), "invalid number \"1.2.3\"");
    EXPECT_EQ(ErrorFor("-").Message(), "invalid number \"-\"");
    EXPECT_EQ(ErrorFor("1e999").Message(), "invalid number \"1e999\"");
    EXPECT_EQ(ErrorFor("12abc").Message(), "invalid number \"12abc\"");
    EXPECT_EQ(ErrorFor("+-1").Message(), "invalid number \"+-1\"");
    EXPECT_EQ(ErrorFor("-inf").Message(), "invalid number \"-inf\"");
}

TEST(Tokenizer, UnknownEscape) {
    SceneError e = ErrorFor("\"a\\qb\"");
    EXPECT_EQ(e.Message(), "unknown escape sequence \"\\q\"");
}

TEST(Tokenizer, SkipsByteOrderMark) {
    Tokenizer tok("\xEF\xBB\xBFWorldBegin", "f");
    Token t = tok.Next();
    EXPECT_EQ(t.text, "WorldBegin");
    EXPECT_EQ(t.column, 1);
}

// 900,000 tokens in one array: each counted and its value read (how fast is bench's business:
// docs/BENCHMARKS.md).
TEST(Tokenizer, LargeInputReadsEveryToken) {
    std::string text = "\"point P\" [";
    for (int i = 0; i < 300000; ++i) text += " 1.25 -3e-2 7";
    text += "]";
    Tokenizer tok(text, "big");
    size_t count = 0;
    double sum = 0;
    for (Token t = tok.Next(); t.kind != TokenKind::End; t = tok.Next()) {
        ++count;
        sum += t.number;
    }
    EXPECT_EQ(count, 900003u);
    EXPECT_NEAR(sum, 300000 * (1.25 - 0.03 + 7), 1e-3);
}

}  // namespace
}  // namespace prism
