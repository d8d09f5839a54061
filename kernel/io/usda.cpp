// USD ASCII (.usda) BasisCurves. The reader is a real tokenizer for the text format: comments,
// layer and prim metadata blocks, other prims (Xform parents, Meshes, Scopes...), relationships,
// timeSamples and connections are understood and skipped where they do not matter. Every
// `def BasisCurves` prim in the file is read and the curves are concatenated in file order.
// The writer produces one linear BasisCurves prim (../shared/NOTES.md: always write `type`).
#include "kernel/io/formats.h"
#include "kernel/math/spline.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>

namespace groom::io {

namespace {

// --- Tokenizer -------------------------------------------------------------------------------------

enum class Tok { End, Ident, Number, String, Punct, Path, Asset };

struct Token {
    Tok kind = Tok::End;
    std::string_view text;  ///< for String: the raw text between the quotes (escapes not yet decoded)
    size_t line = 0;
    bool triple = false;    ///< a """triple-quoted""" string
};

bool ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':' || c == '.'; }
bool number_start(char c) { return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.'; }

class Lexer {
public:
    explicit Lexer(const FileBytes& f) : file_(f), text_(f.data) {}

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
    [[noreturn]] void fail(const Token& t, const std::string& expected) const
    {
        fail_at_line(file_.name, t.line ? t.line : line_, expected + ", found " + describe(t));
    }
    static std::string describe(const Token& t)
    {
        switch (t.kind) {
            case Tok::End: return "end of file";
            case Tok::String: return "string \"" + std::string(t.text.substr(0, 40)) + (t.text.size() > 40 ? "...\"" : "\"");
            default: return describe_found(t.text);
        }
    }
    const std::string& name() const { return file_.name; }

    /// Fast path for the big numeric arrays (points, widths, primvars): parses `[n, ...]` or
    /// `[(a, b, c), ...]` straight from the text, skipping the token machinery. Returns false and
    /// consumes nothing when anything unusual is there (comments, nan/inf, a malformed number):
    /// the token parser then takes over and reports errors with their line.
    bool scan_numeric_array(AttrType type, AttributeData& data)
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

    /// Checks and consumes the `#usda 1.0` header line.
    void header()
    {
        if (text_.rfind("#usda", 0) != 0) {
            const std::string_view first = text_.substr(0, std::min<size_t>(text_.find('\n'), 20));
            fail_at_line(file_.name, 1, "expected the '#usda 1.0' header, found " + describe_found(first));
        }
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    }

private:
    Token lex()
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

    void skip_space_and_comments()
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

    const FileBytes& file_;
    std::string_view text_;
    size_t pos_ = 0;
    size_t line_ = 1;
    Token peeked_;
    bool has_peek_ = false;
};

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

// --- Values ----------------------------------------------------------------------------------------

/// What a USD value type becomes in a CurveSet column; nullopt = a type we do not keep (skipped).
std::optional<AttrType> column_type(std::string_view usd_type)
{
    static const std::map<std::string_view, AttrType> types{
        {"float", AttrType::Float},      {"double", AttrType::Float},     {"half", AttrType::Float},
        {"int", AttrType::Int32},        {"bool", AttrType::Int32},       {"uchar", AttrType::Int32},
        {"uint", AttrType::Int64},       {"int64", AttrType::Int64},      {"uint64", AttrType::Int64},
        {"float3", AttrType::Float3},    {"double3", AttrType::Float3},   {"half3", AttrType::Float3},
        {"point3f", AttrType::Float3},   {"point3d", AttrType::Float3},   {"point3h", AttrType::Float3},
        {"normal3f", AttrType::Float3},  {"normal3d", AttrType::Float3},  {"normal3h", AttrType::Float3},
        {"vector3f", AttrType::Float3},  {"vector3d", AttrType::Float3},  {"vector3h", AttrType::Float3},
        {"color3f", AttrType::Float3},   {"color3d", AttrType::Float3},   {"color3h", AttrType::Float3},
        {"string", AttrType::String},    {"token", AttrType::String},
    };
    const auto it = types.find(usd_type);
    if (it == types.end()) return std::nullopt;
    return it->second;
}

class Parser {
public:
    explicit Parser(const FileBytes& f) : lex_(f) {}

    /// Skips one value of any shape: a scalar, a (tuple), a [list] or a {dictionary}.
    void skip_value()
    {
        const Token t = lex_.next();
        if (t.kind == Tok::Punct && (t.text[0] == '(' || t.text[0] == '[' || t.text[0] == '{')) {
            int depth = 1;
            while (depth > 0) {
                const Token u = lex_.next();
                if (u.kind == Tok::End) lex_.fail(u, "expected the closing bracket of the value opened on line " + std::to_string(t.line));
                if (u.kind == Tok::Punct) {
                    const char c = u.text[0];
                    depth += (c == '(' || c == '[' || c == '{') ? 1 : (c == ')' || c == ']' || c == '}') ? -1 : 0;
                }
            }
            return;
        }
        if (t.kind == Tok::End || t.kind == Tok::Punct) lex_.fail(t, "expected a value");
        // A reference is an asset path optionally followed by a prim path: @./a.usda@</root>.
        if (t.kind == Tok::Asset && lex_.peek().kind == Tok::Path) lex_.next();
    }

    float number_float()
    {
        const Token t = lex_.next();
        float v = 0;
        if ((t.kind == Tok::Number || t.kind == Tok::Ident) && parse_float(t.text, v)) return v;
        lex_.fail(t, "expected a number");
    }
    int64_t number_int()
    {
        const Token t = lex_.next();
        int64_t v = 0;
        if (t.kind == Tok::Number && parse_int(t.text, v)) return v;
        if (t.kind == Tok::Ident && (t.text == "true" || t.text == "false")) return t.text == "true";
        lex_.fail(t, "expected an integer");
    }
    float3 tuple3()
    {
        lex_.expect_punct('(', "opening a 3-tuple");
        float3 p;
        p.x = number_float();
        lex_.expect_punct(',', "between tuple components");
        p.y = number_float();
        lex_.expect_punct(',', "between tuple components");
        p.z = number_float();
        lex_.expect_punct(')', "closing a 3-tuple");
        return p;
    }
    std::string string_value()
    {
        const Token t = lex_.next();
        if (t.kind == Tok::String) return decode_string(t);
        lex_.fail(t, "expected a string");
    }

    /// One scalar of `type` appended to `data`.
    void element(AttrType type, AttributeData& data)
    {
        switch (type) {
            case AttrType::Float: std::get<std::vector<float>>(data).push_back(number_float()); break;
            case AttrType::Int32: {
                const Token& t = lex_.peek();
                const int64_t v = number_int();
                if (v < INT32_MIN || v > INT32_MAX) lex_.fail(t, "expected a 32-bit integer");
                std::get<std::vector<int32_t>>(data).push_back(static_cast<int32_t>(v));
                break;
            }
            case AttrType::Int64: std::get<std::vector<int64_t>>(data).push_back(number_int()); break;
            case AttrType::Float3: std::get<std::vector<float3>>(data).push_back(tuple3()); break;
            case AttrType::String: std::get<std::vector<std::string>>(data).push_back(string_value()); break;
        }
    }

    /// A value of `type`: `[a, b, ...]` when `array`, else one scalar. `None` gives no value.
    std::optional<AttributeData> typed_value(AttrType type, bool array)
    {
        if (array) {
            AttributeData fast = make_attribute_data(type, 0);
            if (lex_.scan_numeric_array(type, fast)) return fast;
        }
        if (lex_.peek().kind == Tok::Ident && lex_.peek().text == "None") {
            lex_.next();
            return std::nullopt;
        }
        AttributeData data = make_attribute_data(type, 0);
        if (!array) {
            element(type, data);
            return data;
        }
        lex_.expect_punct('[', "opening an array value");
        if (lex_.accept_punct(']')) return data;
        for (;;) {
            element(type, data);
            if (lex_.accept_punct(']')) break;
            const Token t = lex_.next();
            if (t.kind != Tok::Punct || t.text[0] != ',') lex_.fail(t, "expected ',' or ']' in an array");
            if (lex_.accept_punct(']')) break;  // trailing comma
        }
        return data;
    }

    // --- Structure --------------------------------------------------------------------------------

    struct Primvar {
        std::string name;             ///< without the "primvars:" prefix, or "widths"
        AttributeData data;
        std::string interpolation;    ///< "" when not authored
        size_t line = 0;
        std::vector<int32_t> indices; ///< indexed primvar (primvars:NAME:indices), empty when not indexed
    };

    struct CurvesPrim {
        std::string path;
        size_t line = 0;
        std::string type = "cubic", basis = "bezier", wrap = "nonperiodic";  // USD schema defaults
        std::optional<std::vector<int32_t>> counts;
        std::optional<std::vector<float3>> points;
        size_t points_line = 0, counts_line = 0;
        std::vector<Primvar> primvars;  ///< widths first when present
    };

    std::vector<CurvesPrim> parse_layer()
    {
        lex_.header();
        if (lex_.peek().kind == Tok::Punct && lex_.peek().text[0] == '(') metadata(nullptr);
        while (lex_.peek().kind != Tok::End) prim("");
        return std::move(found_);
    }

private:
    /// `( key = value ... )`: returns the interpolation when `interpolation` is given.
    void metadata(std::string* interpolation)
    {
        lex_.expect_punct('(', "opening metadata");
        for (;;) {
            const Token t = lex_.next();
            if (t.kind == Tok::Punct && t.text[0] == ')') return;
            if (t.kind == Tok::Punct && t.text[0] == ';') continue;
            if (t.kind == Tok::String) continue;  // a bare doc string
            if (t.kind != Tok::Ident) lex_.fail(t, "expected a metadata key or ')'");
            Token key = t;
            if (key.text == "prepend" || key.text == "append" || key.text == "add" || key.text == "delete" ||
                key.text == "reorder") {
                key = lex_.next();
                if (key.kind != Tok::Ident) lex_.fail(key, "expected a metadata key after '" + std::string(t.text) + "'");
            }
            if (!lex_.accept_punct('=')) continue;  // a key without value
            if (interpolation && key.text == "interpolation") {
                *interpolation = string_value();
            }
            else {
                skip_value();
            }
        }
    }

    /// Prims may nest this deep (scenes nest a few dozen levels). prim() and body() recurse, so
    /// without a limit a file of nested `def`s overflows the stack instead of getting a message.
    static constexpr int kMaxPrimDepth = 1000;
    /// Every open prim holds its full path, so long names nested deep would cost memory quadratic
    /// in the file size; real paths are well under this.
    static constexpr size_t kMaxPathLength = 4096;

    void prim(const std::string& parent)
    {
        struct DepthGuard {
            int& depth;
            ~DepthGuard() { --depth; }
        } guard{++depth_};
        const Token spec = lex_.next();
        if (depth_ > kMaxPrimDepth) {
            throw LimitExceeded(lex_.name() + ":" + std::to_string(spec.line) + ": prims nested deeper than " +
                                std::to_string(kMaxPrimDepth) + " levels; refusing to read further");
        }
        if (spec.kind != Tok::Ident || (spec.text != "def" && spec.text != "over" && spec.text != "class")) {
            lex_.fail(spec, "expected a prim ('def', 'over' or 'class')");
        }
        std::string type_name;
        if (lex_.peek().kind == Tok::Ident) type_name = std::string(lex_.next().text);
        const Token name = lex_.next();
        if (name.kind != Tok::String) lex_.fail(name, "expected the prim's name as a quoted string");
        const std::string path = parent + "/" + decode_string(name);
        if (path.size() > kMaxPathLength) {
            throw LimitExceeded(lex_.name() + ":" + std::to_string(name.line) + ": prim path longer than " +
                                std::to_string(kMaxPathLength) + " characters: " + describe_found(path));
        }
        if (lex_.peek().kind == Tok::Punct && lex_.peek().text[0] == '(') metadata(nullptr);
        lex_.expect_punct('{', "opening the body of prim <" + path + ">");
        const bool curves = spec.text == "def" && type_name == "BasisCurves";
        CurvesPrim cp;
        cp.path = path;
        cp.line = spec.line;
        body(path, curves ? &cp : nullptr);
        if (curves) found_.push_back(std::move(cp));
    }

    void body(const std::string& path, CurvesPrim* cp)
    {
        for (;;) {
            const Token& t = lex_.peek();
            if (t.kind == Tok::End) lex_.fail(t, "expected '}' closing prim <" + path + ">");
            if (t.kind == Tok::Punct && t.text[0] == '}') {
                lex_.next();
                return;
            }
            if (t.kind == Tok::Punct && t.text[0] == ';') {
                lex_.next();
                continue;
            }
            if (t.kind != Tok::Ident) lex_.fail(t, "expected a property, a child prim or '}' in prim <" + path + ">");
            if (t.text == "def" || t.text == "over" || t.text == "class") {
                prim(path);
            }
            else if (t.text == "variantSet") {
                lex_.next();
                lex_.next();  // its name
                lex_.expect_punct('=', "after the variantSet name");
                skip_value();
            }
            else if (t.text == "reorder") {
                lex_.next();
                lex_.next();
                lex_.expect_punct('=', "after 'reorder'");
                skip_value();
            }
            else {
                property(path, cp);
            }
        }
    }

    void property(const std::string& path, CurvesPrim* cp)
    {
        Token t = lex_.next();
        bool uniform = false;
        while (t.kind == Tok::Ident && (t.text == "custom" || t.text == "uniform" || t.text == "varying" || t.text == "config")) {
            uniform = uniform || t.text == "uniform";
            t = lex_.next();
        }
        if (t.kind != Tok::Ident) lex_.fail(t, "expected a property type in prim <" + path + ">");
        const Token type = t;
        if (type.text == "rel") {
            lex_.next();  // relationship name
            if (lex_.accept_punct('=')) skip_value();
            if (lex_.peek().kind == Tok::Punct && lex_.peek().text[0] == '(') metadata(nullptr);
            return;
        }
        bool array = false;
        if (lex_.accept_punct('[')) {
            lex_.expect_punct(']', "after '[' in an array type");
            array = true;
        }
        const Token name = lex_.next();
        if (name.kind != Tok::Ident) lex_.fail(name, "expected a property name after type '" + std::string(type.text) + "'");
        std::string_view pname = name.text;
        std::optional<AttributeData> value;
        bool has_value = false;
        const std::optional<AttrType> ctype = column_type(type.text);
        bool time_samples = false;
        if (pname.size() > 12 && pname.substr(pname.size() - 12) == ".timeSamples") {
            pname.remove_suffix(12);
            time_samples = true;
        }
        const bool connect = pname.find(".connect") != std::string_view::npos;
        if (lex_.accept_punct('=')) {
            has_value = true;
            if (cp && ctype && !connect && wanted(pname)) {
                value = time_samples ? first_time_sample(*ctype, array) : typed_value(*ctype, array);
            }
            else {
                skip_value();
            }
        }
        std::string interpolation;
        if (lex_.peek().kind == Tok::Punct && lex_.peek().text[0] == '(') metadata(&interpolation);
        (void)uniform;
        if (!cp || !has_value || !value || connect) return;
        store(*cp, pname, *ctype, std::move(*value), interpolation, name.line);
    }

    /// `{ time: value, ... }`: the earliest sample (files written for one frame have one).
    std::optional<AttributeData> first_time_sample(AttrType type, bool array)
    {
        lex_.expect_punct('{', "opening timeSamples");
        std::optional<AttributeData> first;
        double first_time = INFINITY;
        while (!lex_.accept_punct('}')) {
            const Token tt = lex_.next();
            double time = 0;
            if (tt.kind != Tok::Number || !parse_double(tt.text, time)) lex_.fail(tt, "expected a time code in timeSamples");
            lex_.expect_punct(':', "after a time code");
            std::optional<AttributeData> v = typed_value(type, array);
            if (time < first_time) {
                first_time = time;
                first = std::move(v);
            }
            lex_.accept_punct(',');
        }
        return first;
    }

    static bool wanted(std::string_view name)
    {
        return name == "points" || name == "curveVertexCounts" || name == "widths" || name == "type" || name == "basis" ||
               name == "wrap" || name.rfind("primvars:", 0) == 0;
    }

    void store(CurvesPrim& cp, std::string_view name, AttrType type, AttributeData value, const std::string& interpolation,
               size_t line)
    {
        auto want = [&](AttrType expected, const char* what) {
            if (type != expected) {
                fail_at_line(lex_.name(), line, std::string("expected ") + what + " for '" + std::string(name) +
                                                    "' in BasisCurves <" + cp.path + ">, found " + type_name(type) + " values");
            }
        };
        auto token_of = [&](const char* what) {
            want(AttrType::String, "a token");
            auto& v = std::get<std::vector<std::string>>(value);
            if (v.size() != 1) fail_at_line(lex_.name(), line, std::string("expected one token for '") + what + "'");
            return v[0];
        };
        if (name == "points") {
            want(AttrType::Float3, "point3f[]");
            cp.points = std::move(std::get<std::vector<float3>>(value));
            cp.points_line = line;
        }
        else if (name == "curveVertexCounts") {
            if (type == AttrType::Int64) {
                std::vector<int32_t> c;
                for (int64_t v : std::get<std::vector<int64_t>>(value)) c.push_back(static_cast<int32_t>(std::clamp<int64_t>(v, -1, INT32_MAX)));
                cp.counts = std::move(c);
            }
            else {
                want(AttrType::Int32, "int[]");
                cp.counts = std::move(std::get<std::vector<int32_t>>(value));
            }
            cp.counts_line = line;
        }
        else if (name == "type") {
            cp.type = token_of("type");
        }
        else if (name == "basis") {
            cp.basis = token_of("basis");
        }
        else if (name == "wrap") {
            cp.wrap = token_of("wrap");
        }
        else if (name == "widths") {
            want(AttrType::Float, "float[]");
            cp.primvars.insert(cp.primvars.begin(), Primvar{"widths", std::move(value), interpolation, line, {}});
        }
        else {
            std::string pv(name.substr(9));  // after "primvars:"
            const size_t suffix = pv.size() >= 8 ? pv.size() - 8 : std::string::npos;
            if (suffix != std::string::npos && pv.compare(suffix, 8, ":indices") == 0) {
                if (type != AttrType::Int32) fail_at_line(lex_.name(), line, "expected int[] for primvars:" + pv);
                pv.resize(suffix);
                indices_[cp.path + "\n" + pv] = std::move(std::get<std::vector<int32_t>>(value));
                return;
            }
            cp.primvars.push_back(Primvar{pv, std::move(value), interpolation, line, {}});
        }
    }

public:
    /// Indexed primvars: attach the `:indices` arrays read anywhere in their prim.
    void attach_indices(std::vector<CurvesPrim>& prims)
    {
        for (CurvesPrim& cp : prims) {
            for (Primvar& pv : cp.primvars) {
                auto it = indices_.find(cp.path + "\n" + pv.name);
                if (it != indices_.end()) pv.indices = std::move(it->second);
            }
        }
    }

private:
    Lexer lex_;
    int depth_ = 0;
    std::vector<CurvesPrim> found_;
    std::map<std::string, std::vector<int32_t>> indices_;
};

// --- From parsed prims to a CurveSet ---------------------------------------------------------------

/// Expands an indexed primvar: out[i] = values[indices[i]].
AttributeData expand_indexed(const FileBytes& file, const Parser::Primvar& pv)
{
    return std::visit(
        [&](const auto& values) -> AttributeData {
            using V = std::decay_t<decltype(values)>;
            V out;
            out.reserve(pv.indices.size());
            for (int32_t i : pv.indices) {
                if (i < 0 || static_cast<size_t>(i) >= values.size()) {
                    fail_at_line(file.name, pv.line, "primvars:" + pv.name + ":indices holds " + std::to_string(i) + ", out of range (" +
                                                         std::to_string(values.size()) + " values)");
                }
                out.push_back(values[i]);
            }
            return out;
        },
        pv.data);
}

size_t data_size(const AttributeData& d)
{
    return std::visit([](const auto& v) { return v.size(); }, d);
}

/// Per-curve count of `varying` values for a cubic curve of n control points.
int64_t varying_count(int64_t n, bool cubic, bool pinned)
{
    if (!cubic) return n;
    return pinned ? n : std::max<int64_t>(n - 2, 0);
}

/// One BasisCurves prim as a linear CurveSet (cubic curves evaluated into polylines).
CurveSet build_prim(const FileBytes& file, Parser::CurvesPrim& cp, const CurveReadOptions& options)
{
    const std::string where = file.name + ":" + std::to_string(cp.line) + ": BasisCurves <" + cp.path + ">";
    if (!cp.points) throw ParseError(where + " has no 'points'");
    if (!cp.counts) throw ParseError(where + " has no 'curveVertexCounts'");
    const std::vector<float3>& pts = *cp.points;
    const std::vector<int32_t>& counts = *cp.counts;
    int64_t total = 0;
    for (size_t c = 0; c < counts.size(); ++c) {
        if (counts[c] < 0) {
            fail_at_line(file.name, cp.counts_line, "curveVertexCounts[" + std::to_string(c) + "] is negative (" + std::to_string(counts[c]) + ")");
        }
        total += counts[c];
    }
    if (total != static_cast<int64_t>(pts.size())) {
        fail_at_line(file.name, cp.counts_line, "curveVertexCounts sum to " + std::to_string(total) + " but 'points' (line " +
                                                    std::to_string(cp.points_line) + ") has " + std::to_string(pts.size()) + " points");
    }
    for (size_t i = 0; i < pts.size(); ++i) {
        if (!isfinite(pts[i])) fail_at_line(file.name, cp.points_line, "points[" + std::to_string(i) + "] is not finite (NaN or inf)");
    }

    bool cubic = false, pinned = false;
    CubicBasis basis = CubicBasis::CatmullRom;
    if (cp.type == "cubic") {
        cubic = true;
        if (cp.basis == "catmullRom") basis = CubicBasis::CatmullRom;
        else if (cp.basis == "bspline") basis = CubicBasis::BSpline;
        else throw ParseError(where + ": cubic basis '" + cp.basis + "' is not supported (expected catmullRom or bspline; "
                              "write 'uniform token basis' explicitly: the USD default is bezier)");
        if (cp.wrap == "pinned") pinned = true;
        else if (cp.wrap != "nonperiodic") throw ParseError(where + ": wrap '" + cp.wrap + "' is not supported for cubic curves (expected nonperiodic or pinned)");
        for (size_t c = 0; c < counts.size(); ++c) {
            const int need = pinned ? 2 : 4;
            if (counts[c] < need) {
                fail_at_line(file.name, cp.counts_line, "cubic " + cp.wrap + " curve " + std::to_string(c) + " has " + std::to_string(counts[c]) +
                                                            " points; it needs at least " + std::to_string(need));
            }
        }
    }
    else if (cp.type == "linear") {
        if (cp.wrap == "periodic") throw ParseError(where + ": wrap 'periodic' (closed curves) is not supported; expected nonperiodic");
    }
    else {
        throw ParseError(where + ": curve type '" + cp.type + "' is not supported (expected linear or cubic)");
    }

    // Control-point topology first; cubic curves are evaluated at the end.
    CurveSet cvs = CurveSet::from_counts(std::span<const int32_t>(counts));
    std::copy(pts.begin(), pts.end(), cvs.positions_for_write().begin());
    const int64_t num_curves = static_cast<int64_t>(counts.size()), num_points = total;
    int64_t num_varying = 0;
    for (int32_t n : counts) num_varying += varying_count(n, cubic, pinned);

    // Varying primvars of cubic curves live on segment ends; kept aside and interpolated below.
    std::vector<Parser::Primvar*> varying;
    for (Parser::Primvar& pv : cp.primvars) {
        AttributeData data = pv.indices.empty() ? std::move(pv.data) : expand_indexed(file, pv);
        const int64_t n = static_cast<int64_t>(data_size(data));
        std::string interp = pv.interpolation;
        if (interp.empty()) {
            // Not authored: infer from the count (USD's default is constant for primvars, vertex for widths).
            interp = n == num_points ? "vertex" : n == num_curves ? "uniform" : n == 1 ? "constant" : pv.name == "widths" ? "vertex" : "constant";
        }
        if (interp == "faceVarying") interp = "varying";
        if (interp == "varying" && !cubic) interp = "vertex";
        int64_t expected = 0;
        Domain domain = Domain::Point;
        if (interp == "vertex") expected = num_points, domain = Domain::Point;
        else if (interp == "varying") expected = num_varying, domain = Domain::Point;
        else if (interp == "uniform") expected = num_curves, domain = Domain::Curve;
        else if (interp == "constant") expected = 1, domain = Domain::Detail;
        else fail_at_line(file.name, pv.line, "unknown interpolation '" + pv.interpolation + "' for " + pv.name);
        const AttrType type = static_cast<AttrType>(data.index());
        if (type == AttrType::String && domain != Domain::Detail) continue;  // per-element strings: no column type for them
        if (n != expected) {
            if (domain == Domain::Detail) continue;  // an array-valued constant (elementSize > 1): not representable, skipped
            fail_at_line(file.name, pv.line, (pv.name == "widths" ? std::string("widths") : "primvars:" + pv.name) + " has " +
                                                 std::to_string(n) + " values but interpolation '" + interp + "' needs " +
                                                 std::to_string(expected));
        }
        pv.data = std::move(data);
        pv.interpolation = interp;
        if (pv.name == "widths") {
            // widths -> point float `width` (diameters), whatever the authored interpolation.
            const auto& w = std::get<std::vector<float>>(pv.data);
            if (interp == "varying") {
                varying.push_back(&pv);
                continue;
            }
            auto dst = cvs.add<float>(Domain::Point, attr::width);
            for (int64_t c = 0; c < num_curves; ++c) {
                const IndexRange r = cvs.points_of(c);
                for (int64_t i = r.begin; i < r.end; ++i) dst[i] = domain == Domain::Point ? w[i] : domain == Domain::Curve ? w[c] : w[0];
            }
            continue;
        }
        if (interp == "varying") {
            varying.push_back(&pv);
            continue;
        }
        if (cvs.attributes(domain).find(pv.name)) continue;  // a second primvar of the same name (widths vs primvars:width)
        Attribute& a = cvs.attributes(domain).add(pv.name, domain, type, 0);
        a.data = std::move(pv.data);
    }
    if (!cubic) {
        cvs.validate(file.name);
        return cvs;
    }

    // Evaluate cubic curves (and their vertex / varying primvars) into polylines.
    const int k = std::max(options.cubic_samples_per_segment, 1);
    std::vector<int64_t> out_counts(counts.size());
    for (size_t c = 0; c < counts.size(); ++c) out_counts[c] = (pinned ? counts[c] - 1 : counts[c] - 3) * int64_t(k) + 1;
    CurveSet out = CurveSet::from_counts(out_counts);
    for (const Attribute& a : cvs.attributes(Domain::Curve).all()) out.attributes(Domain::Curve).all().push_back(a);
    for (const Attribute& a : cvs.attributes(Domain::Detail).all()) out.attributes(Domain::Detail).all().push_back(a);
    auto eval3 = [&](std::span<const float3> src, std::span<float3> dst) {
        for (size_t c = 0; c < counts.size(); ++c) {
            const IndexRange r = cvs.points_of(c);
            const std::vector<float3> e = evaluate_cubic(src.subspan(r.begin, r.size()), basis, pinned, k);
            std::copy(e.begin(), e.end(), dst.begin() + out.points_of(c).begin);
        }
    };
    // Sample j of a curve lies in segment j / k at parameter (j % k) / k; the last sample ends the last segment.
    auto segment_of = [&](int64_t j, int64_t segments, int64_t& s, float& t) {
        s = std::min<int64_t>(j / k, segments - 1);
        t = static_cast<float>(j - s * k) / k;
    };
    for (const Attribute& a : cvs.attributes(Domain::Point).all()) {
        Attribute& dst = out.attributes(Domain::Point).add(a.name, Domain::Point, a.type(), out.num_points());
        if (a.type() == AttrType::Float3) {
            eval3(a.values<float3>(), dst.values<float3>());
        }
        else if (a.type() == AttrType::Float) {
            std::vector<float3> packed(a.size()), result(out.num_points());
            auto src = a.values<float>();
            for (size_t i = 0; i < packed.size(); ++i) packed[i] = {src[i], 0.0f, 0.0f};
            eval3(packed, result);
            auto d = dst.values<float>();
            for (size_t i = 0; i < result.size(); ++i) d[i] = result[i].x;
        }
        else {
            // Integers cannot be blended: each sample takes its nearest control point.
            std::visit(
                [&](const auto& src) {
                    using V = std::decay_t<decltype(src)>;
                    if constexpr (!std::is_same_v<V, std::vector<float>> && !std::is_same_v<V, std::vector<float3>>) {
                        auto& d = std::get<V>(dst.data);
                        for (size_t c = 0; c < counts.size(); ++c) {
                            const int64_t segs = pinned ? counts[c] - 1 : counts[c] - 3;
                            const int64_t first_cv = cvs.points_of(c).begin + (pinned ? 0 : 1);
                            const IndexRange r = out.points_of(c);
                            for (int64_t j = 0; j < r.size(); ++j) {
                                int64_t s;
                                float t;
                                segment_of(j, segs, s, t);
                                d[r.begin + j] = src[first_cv + s + (t >= 0.5f ? 1 : 0)];
                            }
                        }
                    }
                },
                a.data);
        }
    }
    for (Parser::Primvar* pv : varying) {
        // Varying values sit on segment ends and blend linearly along each segment.
        const std::string name = pv->name == "widths" ? std::string(attr::width) : pv->name;
        const AttrType type = static_cast<AttrType>(pv->data.index());
        Attribute& dst = out.attributes(Domain::Point).add(name, Domain::Point, type, out.num_points());
        int64_t base = 0;
        for (size_t c = 0; c < counts.size(); ++c) {
            const int64_t segs = pinned ? counts[c] - 1 : counts[c] - 3;
            const IndexRange r = out.points_of(c);
            for (int64_t j = 0; j < r.size(); ++j) {
                int64_t s;
                float t;
                segment_of(j, segs, s, t);
                std::visit(
                    [&](const auto& src) {
                        using V = std::decay_t<decltype(src)>;
                        auto& d = std::get<V>(dst.data);
                        if constexpr (std::is_same_v<V, std::vector<float>>) d[r.begin + j] = src[base + s] + (src[base + s + 1] - src[base + s]) * t;
                        else if constexpr (std::is_same_v<V, std::vector<float3>>) d[r.begin + j] = lerp(src[base + s], src[base + s + 1], t);
                        else d[r.begin + j] = src[base + s + (t >= 0.5f ? 1 : 0)];
                    },
                    pv->data);
            }
            base += varying_count(counts[c], true, pinned);
        }
    }
    eval3(cvs.positions_for_write(), out.positions_for_write());
    out.validate(file.name);
    return out;
}

/// Appends `src` after `dst`. Point and curve columns present in both (same type) are kept; a column
/// missing from either side cannot be filled honestly and is dropped. Detail values come from `dst`.
void append_curves(CurveSet& dst, const CurveSet& src)
{
    if (dst.num_curves() == 0 && dst.attributes(Domain::Point).count() == 1 && dst.attributes(Domain::Detail).count() == 0) {
        dst = src;
        return;
    }
    const size_t old_points = dst.num_points(), old_curves = dst.num_curves();
    std::vector<int64_t> offsets(dst.offsets().begin(), dst.offsets().end());
    for (size_t c = 1; c <= src.num_curves(); ++c) offsets.push_back(static_cast<int64_t>(old_points) + src.offsets()[c]);
    for (Domain d : {Domain::Point, Domain::Curve}) {
        std::vector<std::string> drop;
        for (Attribute& a : dst.attributes(d).all()) {
            const Attribute* b = src.attributes(d).find(a.name);
            if (!b || b->type() != a.type()) {
                drop.push_back(a.name);
                continue;
            }
            std::visit(
                [&](auto& v) {
                    const auto& w = std::get<std::decay_t<decltype(v)>>(b->data);
                    v.resize(d == Domain::Point ? old_points : old_curves);
                    v.insert(v.end(), w.begin(), w.end());
                },
                a.data);
        }
        for (const std::string& n : drop) dst.attributes(d).remove(n);
    }
    dst.set_offsets(std::move(offsets));
}

// --- Writer ----------------------------------------------------------------------------------------

bool valid_usd_name(std::string_view n)
{
    if (n.empty() || !ident_start(n[0])) return false;
    for (size_t i = 0; i < n.size(); ++i) {
        const char c = n[i];
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':')) return false;
        if (c == ':' && (i + 1 == n.size() || !ident_start(n[i + 1]))) return false;
    }
    return true;
}

void append_escaped(std::string& out, std::string_view s)
{
    out += '"';
    for (char c : s) {
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\t': out += "\\t"; break;
            default: out += c;
        }
    }
    out += '"';
}

void append_value(std::string& out, float v) { append_number(out, v); }
void append_value(std::string& out, int32_t v) { append_number(out, v); }
void append_value(std::string& out, int64_t v) { append_number(out, v); }
void append_value(std::string& out, const float3& v)
{
    out += '(';
    append_number(out, v.x);
    out += ", ";
    append_number(out, v.y);
    out += ", ";
    append_number(out, v.z);
    out += ')';
}
void append_value(std::string& out, const std::string& v) { append_escaped(out, v); }

/// `[a, b, ...]`, with a line break after each curve for point columns (per_line = curve offsets) or
/// every 16 values otherwise, so the file stays readable and diffable.
template <class T>
void append_array(std::string& out, std::span<const T> values, std::span<const int64_t> breaks, const char* indent)
{
    out += "[";
    size_t next_break = 1;
    for (size_t i = 0; i < values.size(); ++i) {
        bool brk = false;
        if (!breaks.empty()) {
            while (next_break < breaks.size() && breaks[next_break] <= static_cast<int64_t>(i)) {
                brk = brk || breaks[next_break] == static_cast<int64_t>(i);
                ++next_break;
            }
        }
        else {
            brk = i > 0 && i % 16 == 0;
        }
        if (i > 0) out += brk ? "," : ", ";
        if (brk) {
            out += '\n';
            out += indent;
        }
        append_value(out, values[i]);
    }
    out += "]";
}

const char* usd_scalar_type(AttrType t)
{
    switch (t) {
        case AttrType::Float: return "float";
        case AttrType::Int32: return "int";
        case AttrType::Int64: return "int64";
        case AttrType::Float3: return "float3";
        case AttrType::String: return "string";
    }
    return "?";
}

}  // namespace

CurveSet read_usda(const FileBytes& file, const CurveReadOptions& options)
{
    Parser parser(file);
    std::vector<Parser::CurvesPrim> prims = parser.parse_layer();
    parser.attach_indices(prims);
    if (prims.empty()) throw ParseError(file.name + ": expected a 'def BasisCurves' prim, found none");
    CurveSet all;
    for (Parser::CurvesPrim& cp : prims) append_curves(all, build_prim(file, cp, options));
    all.validate(file.name);
    return all;
}

std::string write_usda(const CurveSet& curves)
{
    // Check names first so no partial text is produced for an attribute USD cannot name.
    std::map<std::string, Domain> seen;
    for (Domain d : {Domain::Point, Domain::Curve, Domain::Detail}) {
        for (const Attribute& a : curves.attributes(d).all()) {
            if (d == Domain::Point && a.name == attr::P) continue;
            if (!valid_usd_name(a.name)) {
                throw InvalidParam("usda: " + std::string(domain_name(d)) + " attribute '" + a.name +
                                   "' is not a valid USD property name (letters, digits, '_', ':' namespaces)");
            }
            if (a.type() == AttrType::String && d != Domain::Detail) {
                throw InvalidParam("usda: " + std::string(domain_name(d)) + " attribute '" + a.name + "' holds strings; only detail strings can be written");
            }
            const bool is_widths = d == Domain::Point && a.name == attr::width && a.type() == AttrType::Float;
            if (is_widths) continue;
            if (auto [it, fresh] = seen.emplace(a.name, d); !fresh) {
                throw InvalidParam("usda: attribute '" + a.name + "' exists on both the " + domain_name(it->second) + " and " + domain_name(d) +
                                   " domains; USD primvars need distinct names");
            }
        }
    }

    std::string out;
    out.reserve(curves.num_points() * 40 + curves.num_curves() * 6 + 1024);
    out += "#usda 1.0\n(\n    defaultPrim = \"groom\"\n    doc = \"Written by groom " GROOM_VERSION "\"\n    upAxis = \"Y\"\n)\n\n";
    out += "def BasisCurves \"groom\"\n{\n";
    out += "    uniform token type = \"linear\"\n";
    out += "    uniform token wrap = \"nonperiodic\"\n";
    std::vector<int32_t> counts(curves.num_curves());
    for (size_t c = 0; c < counts.size(); ++c) {
        const int64_t n = curves.points_in(c);
        if (n > INT32_MAX) throw InvalidParam("usda: curve " + std::to_string(c) + " has more than 2^31 points");
        counts[c] = static_cast<int32_t>(n);
    }
    out += "    int[] curveVertexCounts = ";
    append_array<int32_t>(out, counts, {}, "        ");
    out += "\n    point3f[] points = ";
    append_array<float3>(out, curves.positions(), curves.offsets(), "        ");
    out += "\n";

    // Extent: the bounds grown by the largest radius, as UsdGeomBasisCurves::ComputeExtent does.
    const auto width = curves.find<float>(Domain::Point, attr::width);
    Bounds3 b = curves.bounds();
    if (!b.empty()) {
        float r = 0;
        for (float w : width)
            if (std::isfinite(w)) r = std::max(r, 0.5f * w);
        const float3 lo = b.lo - float3(r, r, r), hi = b.hi + float3(r, r, r);
        out += "    float3[] extent = [";
        append_value(out, lo);
        out += ", ";
        append_value(out, hi);
        out += "]\n";
    }
    if (!width.empty()) {
        out += "    float[] widths = ";
        append_array<float>(out, width, curves.offsets(), "        ");
        out += " (\n        interpolation = \"vertex\"\n    )\n";
    }
    for (Domain d : {Domain::Point, Domain::Curve, Domain::Detail}) {
        const char* interp = d == Domain::Point ? "vertex" : d == Domain::Curve ? "uniform" : "constant";
        for (const Attribute& a : curves.attributes(d).all()) {
            if (d == Domain::Point && (a.name == attr::P || (a.name == attr::width && a.type() == AttrType::Float))) continue;
            out += "    ";
            out += usd_scalar_type(a.type());
            if (d != Domain::Detail) out += "[]";
            out += " primvars:" + a.name + " = ";
            std::visit(
                [&](const auto& v) {
                    using T = typename std::decay_t<decltype(v)>::value_type;
                    if (d == Domain::Detail) append_value(out, v[0]);
                    else append_array<T>(out, v, d == Domain::Point ? curves.offsets() : std::span<const int64_t>(), "        ");
                },
                a.data);
            out += " (\n        interpolation = \"";
            out += interp;
            out += "\"\n    )\n";
        }
    }
    out += "}\n";
    return out;
}

}  // namespace groom::io
