// The .usda grammar: layer metadata, prims of any type (Xform parents, Meshes, Scopes...), properties, metadata,
// relationships, timeSamples and connections are understood and skipped where they do not matter; BasisCurves
// properties are kept (usda_syntax.h). Apart from the lexer (characters) and the builder (geometry).
#include "kernel/io/usda_lexer.h"
#include "kernel/io/usda_syntax.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

namespace groom::io::usda {

namespace {

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

}  // namespace

std::vector<CurvesPrim> parse_curves_prims(const FileBytes& file)
{
    Parser parser(file);
    std::vector<CurvesPrim> prims = parser.parse_layer();
    parser.attach_indices(prims);
    return prims;
}

}  // namespace groom::io::usda
