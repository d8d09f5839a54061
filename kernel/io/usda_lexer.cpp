// The USD ASCII tokenizer (usda_lexer.h): strings, paths, asset paths, identifiers, numbers and
// punctuation, with comments skipped and lines counted for messages; and the fast path that reads
// big numeric arrays straight from the text.
#include "kernel/io/usda_lexer.h"

#include <algorithm>
#include <charconv>

namespace groom::io::usda {

void Lexer::fail(const Token& t, const std::string& expected) const
{
    fail_at_line(file_.name, t.line ? t.line : line_, expected + ", found " + describe(t));
}

std::string Lexer::describe(const Token& t)
{
    switch (t.kind) {
        case Tok::End: return "end of file";
        case Tok::String: return "string \"" + std::string(t.text.substr(0, 40)) + (t.text.size() > 40 ? "...\"" : "\"");
        default: return describe_found(t.text);
    }
}

bool Lexer::scan_numeric_array(AttrType type, AttributeData& data)
{
    if (has_peek_ || type == AttrType::String) return false;
    const size_t save_pos = pos_, save_line = line_;
    auto ws = [&] {
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (c == '\n') ++line_;
            else if (c != ' ' && c != '\t' && c != '\r') break;
            ++pos_;
        }
    };
    auto lit = [&](char c) {
        ws();
        if (pos_ < text_.size() && text_[pos_] == c) {
            ++pos_;
            return true;
        }
        return false;
    };
    auto number = [&](auto& out) {
        ws();
        const size_t start = pos_;
        while (pos_ < text_.size() && (std::isdigit(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '.' || text_[pos_] == '-' ||
                                       text_[pos_] == '+' || text_[pos_] == 'e' || text_[pos_] == 'E'))
            ++pos_;
        const char* b = text_.data() + start;
        if (start < pos_ && *b == '+') ++b;
        const auto res = std::from_chars(b, text_.data() + pos_, out);
        return start < pos_ && res.ec == std::errc() && res.ptr == text_.data() + pos_;
    };
    auto give_up = [&] {
        pos_ = save_pos;
        line_ = save_line;
        data = make_attribute_data(type, 0);
        return false;
    };
    if (!lit('[')) return give_up();
    if (lit(']')) return true;
    for (;;) {
        bool ok = true;
        switch (type) {
            case AttrType::Float: {
                float v;
                ok = number(v);
                std::get<std::vector<float>>(data).push_back(v);
                break;
            }
            case AttrType::Int32: {
                int32_t v;
                ok = number(v);
                std::get<std::vector<int32_t>>(data).push_back(v);
                break;
            }
            case AttrType::Int64: {
                int64_t v;
                ok = number(v);
                std::get<std::vector<int64_t>>(data).push_back(v);
                break;
            }
            case AttrType::Float3: {
                float3 v;
                ok = lit('(') && number(v.x) && lit(',') && number(v.y) && lit(',') && number(v.z) && lit(')');
                std::get<std::vector<float3>>(data).push_back(v);
                break;
            }
            case AttrType::String: ok = false; break;
        }
        if (!ok) return give_up();
        if (lit(']')) return true;
        if (!lit(',')) return give_up();
        if (lit(']')) return true;  // trailing comma
    }
}

void Lexer::header()
{
    if (text_.rfind("#usda", 0) != 0) {
        const std::string_view first = text_.substr(0, std::min<size_t>(text_.find('\n'), 20));
        fail_at_line(file_.name, 1, "expected the '#usda 1.0' header, found " + describe_found(first));
    }
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
}

Token Lexer::lex()
{
    skip_space_and_comments();
    Token t;
    t.line = line_;
    if (pos_ >= text_.size()) return t;
    const char c = text_[pos_];
    const size_t start = pos_;
    if (c == '"' || c == '\'') {
        t.kind = Tok::String;
        if (text_.compare(pos_, 3, std::string(3, c)) == 0) {
            t.triple = true;
            pos_ += 3;
            const size_t body = pos_;
            const size_t close = text_.find(std::string(3, c), pos_);
            if (close == std::string_view::npos) fail_at_line(file_.name, t.line, "unterminated triple-quoted string");
            for (size_t i = body; i < close; ++i) line_ += text_[i] == '\n';
            t.text = text_.substr(body, close - body);
            pos_ = close + 3;
            return t;
        }
        ++pos_;
        const size_t body = pos_;
        while (pos_ < text_.size() && text_[pos_] != c) {
            if (text_[pos_] == '\n') fail_at_line(file_.name, t.line, "unterminated string (newline inside quotes)");
            if (text_[pos_] == '\\') ++pos_;
            ++pos_;
        }
        if (pos_ >= text_.size()) fail_at_line(file_.name, t.line, "unterminated string at end of file");
        t.text = text_.substr(body, pos_ - body);
        ++pos_;
        return t;
    }
    if (c == '<' || c == '@') {
        // Paths <...> and asset paths @...@ (or @@@...@@@).
        const char close = c == '<' ? '>' : '@';
        t.kind = c == '<' ? Tok::Path : Tok::Asset;
        const bool triple_at = c == '@' && text_.compare(pos_, 3, "@@@") == 0;
        pos_ += triple_at ? 3 : 1;
        const size_t end = triple_at ? text_.find("@@@", pos_) : text_.find(close, pos_);
        if (end == std::string_view::npos) fail_at_line(file_.name, t.line, std::string("unterminated ") + (c == '<' ? "path" : "asset path"));
        t.text = text_.substr(pos_, end - pos_);
        pos_ = end + (triple_at ? 3 : 1);
        return t;
    }
    if (ident_start(c)) {
        t.kind = Tok::Ident;
        while (pos_ < text_.size() && ident_char(text_[pos_])) ++pos_;
        t.text = text_.substr(start, pos_ - start);
        return t;
    }
    if (number_start(c)) {
        t.kind = Tok::Number;
        ++pos_;
        while (pos_ < text_.size()) {
            const char d = text_[pos_];
            const bool exp_sign = (d == '-' || d == '+') && (text_[pos_ - 1] == 'e' || text_[pos_ - 1] == 'E');
            if (std::isalnum(static_cast<unsigned char>(d)) || d == '.' || exp_sign) ++pos_;
            else break;
        }
        t.text = text_.substr(start, pos_ - start);
        return t;
    }
    if (std::string_view("()[]{}=,;:&").find(c) != std::string_view::npos) {
        t.kind = Tok::Punct;
        t.text = text_.substr(pos_, 1);
        ++pos_;
        return t;
    }
    fail_at_line(file_.name, line_, "unexpected character " + describe_found(text_.substr(pos_, 1)));
}

void Lexer::skip_space_and_comments()
{
    while (pos_ < text_.size()) {
        const char c = text_[pos_];
        if (c == '\n') {
            ++line_;
            ++pos_;
        }
        else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            ++pos_;
        }
        else if (c == '#' || (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/')) {
            while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        }
        else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*') {
            const size_t end = text_.find("*/", pos_ + 2);
            if (end == std::string_view::npos) fail_at_line(file_.name, line_, "unterminated /* comment");
            for (size_t i = pos_; i < end; ++i) line_ += text_[i] == '\n';
            pos_ = end + 2;
        }
        else {
            break;
        }
    }
}

std::string decode_string(const Token& t)
{
    std::string out;
    out.reserve(t.text.size());
    for (size_t i = 0; i < t.text.size(); ++i) {
        char c = t.text[i];
        if (c == '\\' && i + 1 < t.text.size()) {
            const char e = t.text[++i];
            switch (e) {
                case 'n': c = '\n'; break;
                case 't': c = '\t'; break;
                case 'r': c = '\r'; break;
                case '0': c = '\0'; break;
                default: c = e; break;  // \" \' \\ and anything else: the character itself
            }
        }
        out += c;
    }
    return out;
}

}  // namespace groom::io::usda
