// Lexer for pbrt scene files: bare words, numbers, quoted strings and brackets, each with the
// 1-based line:column it starts at. Tokens view into the tokenizer's copy of the file text,
// so scanning a large mesh does no per-token allocation.
#pragma once

#include <string>
#include <string_view>

#include "core/error.h"

namespace prism {

enum class TokenKind { Word, Number, String, LBracket, RBracket, End };

struct Token {
    TokenKind kind = TokenKind::End;
    // Words/numbers/brackets: the characters as written. Strings: the contents between the
    // quotes with escapes still raw (see Tokenizer::StringValue).
    std::string_view text;
    double number = 0;                  // the value of a Number token
    bool hasEscapes = false;            // a String token contains a backslash escape
    const std::string *file = nullptr;  // owned by the Tokenizer that produced the token
    int line = 0, column = 0;

    FileLoc Loc() const { return {file ? *file : std::string(), line, column}; }
    bool Is(TokenKind k, std::string_view t) const { return kind == k && text == t; }
};

class Tokenizer {
  public:
    // `filename` only labels locations; the text is taken as given.
    Tokenizer(std::string text, std::string filename);
    Tokenizer(const Tokenizer &) = delete;
    Tokenizer &operator=(const Tokenizer &) = delete;

    // Returns the next token, or an End token at the end of the input. Throws SceneError on
    // malformed input (unterminated string, unknown character, invalid number).
    Token Next();
    // Returns the token Next() would return, without consuming it.
    const Token &Peek();

    // The value of a String token with escapes (\" \\ \n \t \r \b \f \') resolved.
    static std::string StringValue(const Token &t);

    // Readable rendering of a token for messages: strings keep their quotes.
    static std::string Describe(const Token &t);

  private:
    Token Scan();
    void SkipSpaceAndComments();
    [[noreturn]] void Fail(int line, int column, const std::string &msg) const;

    std::string text_;
    std::string filename_;
    size_t pos_ = 0;
    int line_ = 1;
    size_t lineStart_ = 0;  // offset of the first character of the current line
    Token peeked_;
    bool hasPeeked_ = false;
};

}  // namespace prism
