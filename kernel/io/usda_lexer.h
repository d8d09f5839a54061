// The USD ASCII tokenizer: tokens, the Lexer that skips comments and counts lines, and string
// unescaping. Internal to the .usda reader and writer (kernel/io/usda_*.cpp); kept apart from the
// parser so the grammar reads without character-level detail.
#pragma once

#include "kernel/attribute.h"
#include "kernel/io/io_util.h"

#include <cctype>
#include <string>
#include <string_view>

namespace groom::io::usda {

enum class Tok { End, Ident, Number, String, Punct, Path, Asset };

struct Token {
    Tok kind = Tok::End;
    std::string_view text;  ///< for String: the raw text between the quotes (escapes not yet decoded)
    size_t line = 0;
    bool triple = false;    ///< a """triple-quoted""" string
};

inline bool ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
inline bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':' || c == '.'; }
inline bool number_start(char c) { return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.'; }

class Lexer {
public:
    explicit Lexer(const FileBytes& f) : file_(f), text_(f.data) {}

    // peek / next / accept_punct / expect_punct run once per token: kept inline here so the parser's
    // loops still inline them now that the parser lives in its own file.
    const Token& peek()
    {
        if (!has_peek_) {
            peeked_ = lex();
            has_peek_ = true;
        }
        return peeked_;
    }
    Token next()
    {
        const Token t = peek();
        has_peek_ = false;
        return t;
    }
    bool accept_punct(char c)
    {
        if (peek().kind == Tok::Punct && peek().text[0] == c) {
            next();
            return true;
        }
        return false;
    }
    void expect_punct(char c, std::string_view context)
    {
        const Token t = next();
        if (t.kind != Tok::Punct || t.text[0] != c) fail(t, "expected '" + std::string(1, c) + "' " + std::string(context));
    }
    [[noreturn]] void fail(const Token& t, const std::string& expected) const;
    static std::string describe(const Token& t);
    const std::string& name() const { return file_.name; }

    /// Fast path for the big numeric arrays (points, widths, primvars): parses `[n, ...]` or
    /// `[(a, b, c), ...]` straight from the text, skipping the token machinery. Returns false and
    /// consumes nothing when anything unusual is there (comments, nan/inf, a malformed number):
    /// the token parser then takes over and reports errors with their line.
    bool scan_numeric_array(AttrType type, AttributeData& data);

    /// Checks and consumes the `#usda 1.0` header line.
    void header();

private:
    Token lex();
    void skip_space_and_comments();

    const FileBytes& file_;
    std::string_view text_;
    size_t pos_ = 0;
    size_t line_ = 1;
    Token peeked_;
    bool has_peek_ = false;
};

/// The text of a String token with its backslash escapes decoded.
std::string decode_string(const Token& t);

}  // namespace groom::io::usda
