// The .usda grammar: layer metadata, prims of any type, their composition metadata (references, inherits,
// specializes, payloads, variant selections, active, instanceable) with every list op, variant sets, and the
// properties the reader uses (curve data, primvars, xform ops, NURBS data) are kept (usda_syntax.h);
// relationships, connections and everything else are understood and skipped. Apart from the lexer
// (characters), composition (usda_compose.cpp) and the builder (geometry).
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
        if ((t.kind == Tok::Number || t.kind == Tok::Ident) && parse_float(t.text, v)) {
            // A number past float's range became inf without a word (`1e40` in a primvar: a trial);
            // `inf` and `nan` written as such stay what they say.
            const bool digits = std::any_of(t.text.begin(), t.text.end(), [](char c) { return c >= '0' && c <= '9'; });
            if (digits && std::isinf(v)) lex_.fail(t, "expected a number within float's range (3.4e38)");
            return v;
        }
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

    Layer parse_layer()
    {
        lex_.header();
        if (lex_.peek().kind == Tok::Punct && lex_.peek().text[0] == '(') layer_metadata();
        while (lex_.peek().kind != Tok::End) layer_.roots.push_back(prim(""));
        return std::move(layer_);
    }

private:
    static bool is_list_op(std::string_view s)
    {
        return s == "prepend" || s == "append" || s == "add" || s == "delete" || s == "reorder";
    }

    /// `( defaultPrim = "x" ... )` at the top of the file.
    void layer_metadata()
    {
        lex_.expect_punct('(', "opening layer metadata");
        for (;;) {
            const Token t = lex_.next();
            if (t.kind == Tok::Punct && t.text[0] == ')') return;
            if (t.kind == Tok::Punct && t.text[0] == ';') continue;
            if (t.kind == Tok::String) continue;  // the layer's doc string
            if (t.kind != Tok::Ident) lex_.fail(t, "expected a layer metadata key or ')'");
            Token key = t;
            if (is_list_op(key.text)) key = lex_.next();
            if (!lex_.accept_punct('=')) continue;
            if (key.text == "defaultPrim" && lex_.peek().kind == Tok::String) layer_.default_prim = string_value();
            // The two that change what the numbers mean are refused when malformed, as USD's own
            // parser refuses them: skipped, `upAxis = Z` (unquoted) had read as Y-up and
            // `metersPerUnit = "cm"` as no unit, without a word (a trial).
            else if (key.text == "upAxis") {
                if (lex_.peek().kind != Tok::String) lex_.fail(lex_.peek(), "expected upAxis = \"Y\" or \"Z\" (a quoted token)");
                layer_.up_axis = string_value();
            }
            else if (key.text == "metersPerUnit") {
                const Token n = lex_.next();
                double v = 0.0;
                if (n.kind != Tok::Number || !parse_double(n.text, v) || !(v > 0.0) || !std::isfinite(v)) {
                    lex_.fail(n, "expected metersPerUnit > 0, a finite number");
                }
                layer_.meters_per_unit = v;
            }
            else skip_value();
        }
    }

    /// A list of arcs: `</A>`, `@a.usda@</A>`, `[</A>, @b.usda@]`, `None`; each item may carry `( offset = 1 )`.
    std::vector<Arc> arcs()
    {
        std::vector<Arc> out;
        auto item = [&] {
            Arc a;
            const Token t = lex_.next();
            a.line = t.line;
            if (t.kind == Tok::Asset) {
                a.asset = std::string(t.text);  // `@@</X>`: an empty asset path is this file
                if (lex_.peek().kind == Tok::Path) a.path = std::string(lex_.next().text);
            }
            else if (t.kind == Tok::Path) {
                a.path = std::string(t.text);
            }
            else {
                lex_.fail(t, "expected a prim path </...> or an asset path @...@");
            }
            if (lex_.peek().kind == Tok::Punct && lex_.peek().text[0] == '(') skip_value();  // layer offset
            out.push_back(std::move(a));
        };
        if (lex_.peek().kind == Tok::Ident && lex_.peek().text == "None") {
            lex_.next();
            return out;
        }
        if (!lex_.accept_punct('[')) {
            item();
            return out;
        }
        while (!lex_.accept_punct(']')) {
            item();
            if (!lex_.accept_punct(',')) {
                lex_.expect_punct(']', "closing a list of paths");
                break;
            }
        }
        return out;
    }

    /// A list op on a list of arcs: the explicit value replaces, prepend/append/add add, delete removes,
    /// reorder changes nothing we read.
    static void apply_list_op(std::vector<Arc>& list, std::string_view op, std::vector<Arc> value)
    {
        auto same = [](const Arc& a, const Arc& b) { return a.asset == b.asset && a.path == b.path; };
        auto erase = [&](const Arc& v) { list.erase(std::remove_if(list.begin(), list.end(), [&](const Arc& a) { return same(a, v); }), list.end()); };
        if (op.empty()) {
            list = std::move(value);
        }
        else if (op == "delete") {
            for (const Arc& v : value) erase(v);
        }
        else if (op == "prepend") {
            for (const Arc& v : value) erase(v);
            list.insert(list.begin(), value.begin(), value.end());
        }
        else if (op == "append" || op == "add") {
            for (const Arc& v : value) erase(v);
            list.insert(list.end(), value.begin(), value.end());
        }
    }

    /// `variants = { string set = "name" ... }`.
    void variant_selection(PrimSpec& spec)
    {
        lex_.expect_punct('{', "opening the variant selection");
        while (!lex_.accept_punct('}')) {
            const Token ty = lex_.next();
            if (ty.kind == Tok::Punct && ty.text[0] == ';') continue;
            if (ty.kind != Tok::Ident) lex_.fail(ty, "expected 'string' in a variant selection");
            const Token name = lex_.next();
            if (name.kind != Tok::Ident && name.kind != Tok::String) lex_.fail(name, "expected a variant set name");
            const std::string set = name.kind == Tok::String ? decode_string(name) : std::string(name.text);
            lex_.expect_punct('=', "after a variant set name");
            const std::string chosen = string_value();
            spec.variant_selection.emplace_back(set, chosen);
        }
    }

    /// A prim's `( ... )` metadata: composition arcs, active, instanceable, variant selections; the rest skipped.
    void prim_metadata(PrimSpec& spec)
    {
        lex_.expect_punct('(', "opening metadata");
        for (;;) {
            const Token t = lex_.next();
            if (t.kind == Tok::Punct && t.text[0] == ')') return;
            if (t.kind == Tok::Punct && t.text[0] == ';') continue;
            if (t.kind == Tok::String) continue;  // a bare doc string
            if (t.kind != Tok::Ident) lex_.fail(t, "expected a metadata key or ')'");
            Token key = t;
            std::string_view op;
            if (is_list_op(t.text)) {
                op = t.text;
                key = lex_.next();
                if (key.kind != Tok::Ident) lex_.fail(key, "expected a metadata key after '" + std::string(t.text) + "'");
            }
            if (!lex_.accept_punct('=')) continue;  // a key without value
            if (key.text == "references" || key.text == "payload") apply_list_op(spec.references, op, arcs());
            else if (key.text == "inherits") apply_list_op(spec.inherits, op, arcs());
            else if (key.text == "specializes") apply_list_op(spec.specializes, op, arcs());
            else if (key.text == "active") spec.active = number_int() != 0;
            else if (key.text == "instanceable") spec.instanceable = number_int() != 0;
            else if (key.text == "variants") variant_selection(spec);
            else skip_value();
        }
    }

    /// A property's `( ... )` metadata: interpolation and elementSize kept.
    void property_metadata(Property* prop)
    {
        lex_.expect_punct('(', "opening metadata");
        for (;;) {
            const Token t = lex_.next();
            if (t.kind == Tok::Punct && t.text[0] == ')') return;
            if (t.kind == Tok::Punct && t.text[0] == ';') continue;
            if (t.kind == Tok::String) continue;
            if (t.kind != Tok::Ident) lex_.fail(t, "expected a metadata key or ')'");
            Token key = t;
            if (is_list_op(key.text)) {
                key = lex_.next();
                if (key.kind != Tok::Ident) lex_.fail(key, "expected a metadata key after '" + std::string(t.text) + "'");
            }
            if (!lex_.accept_punct('=')) continue;
            if (prop && key.text == "interpolation") {
                prop->interpolation = string_value();
            }
            else if (prop && key.text == "elementSize") {
                const Token& at = lex_.peek();
                const int64_t n = number_int();
                if (n < 1 || n > 1'000'000) lex_.fail(at, "expected an elementSize >= 1");
                prop->element_size = static_cast<int>(n);
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

    struct DepthGuard {
        int& depth;
        ~DepthGuard() { --depth; }
    };
    void check_depth(const Token& at)
    {
        if (depth_ > kMaxPrimDepth) {
            throw LimitExceeded(lex_.name() + ":" + std::to_string(at.line) + ": prims nested deeper than " +
                                std::to_string(kMaxPrimDepth) + " levels; refusing to read further");
        }
    }

    /// One prim; returns its index in layer_.specs.
    int32_t prim(const std::string& parent)
    {
        DepthGuard guard{++depth_};
        const Token spec = lex_.next();
        check_depth(spec);
        if (spec.kind != Tok::Ident || (spec.text != "def" && spec.text != "over" && spec.text != "class")) {
            lex_.fail(spec, "expected a prim ('def', 'over' or 'class')");
        }
        PrimSpec ps;
        ps.specifier = std::string(spec.text);
        ps.line = spec.line;
        if (lex_.peek().kind == Tok::Ident) ps.type_name = std::string(lex_.next().text);
        const Token name = lex_.next();
        if (name.kind != Tok::String) lex_.fail(name, "expected the prim's name as a quoted string");
        ps.name = decode_string(name);
        const std::string path = parent + "/" + ps.name;
        if (path.size() > kMaxPathLength) {
            throw LimitExceeded(lex_.name() + ":" + std::to_string(name.line) + ": prim path longer than " +
                                std::to_string(kMaxPathLength) + " characters: " + describe_found(path));
        }
        if (lex_.peek().kind == Tok::Punct && lex_.peek().text[0] == '(') prim_metadata(ps);
        lex_.expect_punct('{', "opening the body of prim <" + path + ">");
        const auto index = static_cast<int32_t>(layer_.specs.size());
        layer_.specs.push_back(std::move(ps));
        body(path, index);
        return index;
    }

    /// The body of a prim or of a variant, up to and including its closing '}'.
    void body(const std::string& path, int32_t index)
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
                const int32_t child = prim(path);
                layer_.specs[index].children.push_back(child);
            }
            else if (t.text == "variantSet") {
                variant_set(path, index);
            }
            else if (t.text == "reorder") {
                // `reorder nameChildren = [...]` reorders prims (not read); `reorder rel x = ...` is a list op.
                lex_.next();
                const Token& what = lex_.peek();
                if (what.kind == Tok::Ident && (what.text == "nameChildren" || what.text == "properties")) {
                    lex_.next();
                    lex_.expect_punct('=', "after 'reorder'");
                    skip_value();
                }
                else {
                    property(path, layer_.specs[index].props, true);
                }
            }
            else {
                property(path, layer_.specs[index].props);
            }
        }
    }

    /// `variantSet "name" = { "a" (meta) { body } "b" { body } }`.
    void variant_set(const std::string& path, int32_t owner)
    {
        lex_.next();
        const Token name = lex_.next();
        if (name.kind != Tok::String) lex_.fail(name, "expected the variantSet's name as a quoted string");
        VariantSet vs;
        vs.name = decode_string(name);
        lex_.expect_punct('=', "after the variantSet name");
        lex_.expect_punct('{', "opening the variantSet");
        while (!lex_.accept_punct('}')) {
            const Token vname = lex_.next();
            if (vname.kind != Tok::String) lex_.fail(vname, "expected a variant name as a quoted string in variantSet \"" + vs.name + "\"");
            DepthGuard guard{++depth_};
            check_depth(vname);
            PrimSpec body_spec;
            body_spec.specifier = "variant";
            body_spec.name = decode_string(vname);
            body_spec.line = vname.line;
            if (lex_.peek().kind == Tok::Punct && lex_.peek().text[0] == '(') prim_metadata(body_spec);
            lex_.expect_punct('{', "opening variant \"" + body_spec.name + "\"");
            const auto index = static_cast<int32_t>(layer_.specs.size());
            vs.variants.emplace_back(body_spec.name, index);
            layer_.specs.push_back(std::move(body_spec));
            body(path + "{" + vs.name + "=" + layer_.specs[index].name + "}", index);
        }
        layer_.specs[owner].variant_sets.push_back(std::move(vs));
    }

    void property(const std::string& path, std::map<std::string, Property, std::less<>>& props, bool list_op = false)
    {
        Token t = lex_.next();
        while (t.kind == Tok::Ident && (t.text == "custom" || t.text == "uniform" || t.text == "varying" || t.text == "config" || is_list_op(t.text))) {
            list_op = list_op || is_list_op(t.text);
            t = lex_.next();
        }
        if (t.kind != Tok::Ident) lex_.fail(t, "expected a property type in prim <" + path + ">");
        const Token type = t;
        if (type.text == "rel") {
            const Token rname = lex_.next();  // relationship name
            if (rname.kind != Tok::Ident) lex_.fail(rname, "expected a relationship name after 'rel'");
            if (lex_.accept_punct('=')) skip_value();
            if (lex_.peek().kind == Tok::Punct && lex_.peek().text[0] == '(') property_metadata(nullptr);
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
        bool time_samples = false;
        if (pname.size() > 12 && pname.substr(pname.size() - 12) == ".timeSamples") {
            pname.remove_suffix(12);
            time_samples = true;
        }
        const bool other_field = pname.find('.') != std::string_view::npos;  // .connect, .spline...
        const bool keep = !list_op && !other_field && wanted(pname);
        const bool numbers = keep && wants_numbers(pname);
        const std::optional<AttrType> ctype = numbers ? std::nullopt : column_type(type.text);
        Property prop;
        prop.type = std::string(type.text) + (array ? "[]" : "");
        prop.line = name.line;
        bool has_value = false;
        if (lex_.accept_punct('=')) {
            if (keep && (numbers || ctype)) {
                has_value = true;
                if (lex_.peek().kind == Tok::Ident && lex_.peek().text == "None") {
                    lex_.next();
                    prop.blocked = true;
                }
                else if (numbers) {
                    prop.numbers = time_samples ? earliest_sample(prop, [&] {
                        std::vector<double> v;
                        if (lex_.peek().kind == Tok::Ident && lex_.peek().text == "None") lex_.next();
                        else v = number_list();
                        return v;
                    })
                                                 : number_list();
                }
                else {
                    prop.column = time_samples ? earliest_sample(prop, [&] { return typed_value(*ctype, array); }) : typed_value(*ctype, array);
                    if (!prop.column) prop.blocked = true;
                }
            }
            else {
                skip_value();
                // A primvar of a type no column holds (texCoord2f, matrices): kept without a value so
                // that the builder can name it in a warning.
                has_value = keep && pname.rfind("primvars:", 0) == 0;
            }
        }
        if (lex_.peek().kind == Tok::Punct && lex_.peek().text[0] == '(') property_metadata(&prop);
        if (!has_value) {
            // A declaration without a value still carries metadata (interpolation) for a value given
            // elsewhere, e.g. by timeSamples written after it.
            auto it = props.find(pname);
            if (it != props.end() && !prop.interpolation.empty()) it->second.interpolation = prop.interpolation;
            return;
        }
        auto it = props.find(pname);
        if (it != props.end() && prop.interpolation.empty()) prop.interpolation = it->second.interpolation;
        props.insert_or_assign(std::string(pname), std::move(prop));
    }

    /// Any value's numbers, flattened: `1`, `(1, 2, 3)`, `((1,0,0,0), ...)`, `[(0, 1), (2, 3)]`.
    std::vector<double> number_list()
    {
        std::vector<double> out;
        const Token first = lex_.peek();
        int depth = 0;
        do {
            const Token t = lex_.next();
            if (t.kind == Tok::Punct && (t.text[0] == '(' || t.text[0] == '[')) ++depth;
            else if (t.kind == Tok::Punct && (t.text[0] == ')' || t.text[0] == ']')) --depth;
            else if (t.kind == Tok::Punct && t.text[0] == ',' && depth > 0) continue;
            else {
                double v = 0;
                if ((t.kind != Tok::Number && t.kind != Tok::Ident) || !parse_double(t.text, v)) {
                    if (t.kind == Tok::End) lex_.fail(t, "expected the end of the value opened on line " + std::to_string(first.line));
                    lex_.fail(t, "expected a number");
                }
                out.push_back(v);
            }
        } while (depth > 0);
        return out;
    }

    /// `{ time: value, ... }`: the earliest sample's value, read by `read` (files written for one
    /// frame have one); the count and that time go into `prop` for the builder's warning.
    template <class Read> auto earliest_sample(Property& prop, Read read) -> decltype(read())
    {
        lex_.expect_punct('{', "opening timeSamples");
        decltype(read()) first{};
        while (!lex_.accept_punct('}')) {
            const Token tt = lex_.next();
            double time = 0;
            if (tt.kind != Tok::Number || !parse_double(tt.text, time)) lex_.fail(tt, "expected a time code in timeSamples");
            lex_.expect_punct(':', "after a time code");
            auto v = read();
            if (prop.time_samples++ == 0 || time < prop.first_time) {
                prop.first_time = time;
                first = std::move(v);
            }
            lex_.accept_punct(',');
        }
        return first;
    }

    static bool wanted(std::string_view name)
    {
        return name == "points" || name == "curveVertexCounts" || name == "widths" || name == "type" || name == "basis" ||
               name == "wrap" || name == "order" || name == "knots" || name == "ranges" || name == "pointWeights" ||
               name == "xformOpOrder" || name.rfind("primvars:", 0) == 0 || name.rfind("xformOp:", 0) == 0;
    }
    /// Values read as plain numbers (double precision, any shape) rather than as a column.
    static bool wants_numbers(std::string_view name)
    {
        return name == "knots" || name == "ranges" || name == "pointWeights" || name.rfind("xformOp:", 0) == 0;
    }

    Lexer lex_;
    int depth_ = 0;
    Layer layer_;
};

}  // namespace

Layer parse_layer(const FileBytes& file)
{
    Parser parser(file);
    return parser.parse_layer();
}

}  // namespace groom::io::usda
