#include "kernel/io/detail_text.h"

#include "kernel/error.h"
#include "kernel/io/io_util.h"
#include "kernel/units.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace groom::io {

namespace {

std::string escape_line(std::string_view s)
{
    std::string out;
    for (char c : s) {
        if (c == '\\') out += "\\\\";
        else if (c == '\n') out += "\\n";
        else if (c == '\r') out += "\\r";
        else out += c;
    }
    return out;
}

std::string unescape_line(std::string_view s)
{
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '\\' && i + 1 < s.size()) {
            const char e = s[++i];
            out += e == 'n' ? '\n' : e == 'r' ? '\r' : e;
        }
        else {
            out += s[i];
        }
    }
    return out;
}

}  // namespace

bool plain_detail_name(std::string_view name)
{
    if (name.empty()) return false;
    for (char c : name)
        if (c <= ' ' || c > '~') return false;
    return true;
}

std::optional<AttrType> attr_type_named(std::string_view s)
{
    for (AttrType t : {AttrType::Float, AttrType::Int32, AttrType::Int64, AttrType::Float3, AttrType::String})
        if (s == type_name(t)) return t;
    return std::nullopt;
}

std::string detail_value_text(const Attribute& a, const std::string& format)
{
    if (!plain_detail_name(a.name)) throw InvalidParam(format + ": detail attribute name '" + a.name + "' contains spaces or non-ASCII characters");
    std::string spec = std::string(type_name(a.type())) + " ";
    std::visit(
        [&](const auto& v) {
            using T = typename std::decay_t<decltype(v)>::value_type;
            if constexpr (std::is_same_v<T, std::string>) spec += escape_line(v[0]);
            else if constexpr (std::is_same_v<T, float3>) {
                append_number(spec, v[0].x);
                spec += ' ';
                append_number(spec, v[0].y);
                spec += ' ';
                append_number(spec, v[0].z);
            }
            else append_number(spec, v[0]);
        },
        a.data);
    return spec;
}

void set_detail_from_text(CurveSet& cs, const std::string& name, std::string_view text, const std::string& bad_message)
{
    // A name given twice was last-wins without a word (a hand-edited part could carry two shard
    // tags, and merge would check the second); a value past its type's range wrapped; words after
    // the value were dropped.
    if (cs.attributes(Domain::Detail).find(name)) throw ParseError(bad_message + " (detail '" + name + "' given twice)");
    TextCursor cur(text);
    const auto type = attr_type_named(cur.token());
    // The details groom itself reads have one type and meaning: `up_axis z` had turned transform's
    // axis while the .usda writer wrote Y, and `up_axis int 1` failed later naming no file (a trial).
    auto known = [&](std::string_view want) {
        if (type && type_name(*type) != want) throw ParseError(bad_message + " (detail '" + name + "' is " + std::string(want) + ")");
    };
    if (name == "up_axis" || name == "units") known("string");
    if (name == attr::closed) known("int");
    auto bad = [&](const char* why) { throw ParseError(bad_message + " (" + why + ")"); };
    if (!type) bad("expected a type: float, int, int64, float3 or string");
    auto end_of_value = [&] {
        if (!cur.token().empty()) bad("words after the value");
    };
    switch (*type) {
        case AttrType::String: {
            std::string_view rest = cur.rest_of_line();
            if (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
            const std::string value = unescape_line(rest);
            if (name == "up_axis" && value != "Y" && value != "Z") bad("up_axis is Y or Z");
            if (name == "units" && !(meters_per_unit(value) > 0.0)) bad("units is mm, cm, m, in or metres per unit");
            cs.set_detail_string(name, value);
            break;
        }
        case AttrType::Float: {
            float v;
            if (!parse_float(cur.token(), v) || !std::isfinite(v)) bad("expected a finite float");  // (1e40 had become inf: a trial)
            end_of_value();
            cs.add<float>(Domain::Detail, name)[0] = v;
            break;
        }
        case AttrType::Int32:
        case AttrType::Int64: {
            int64_t v;
            if (!parse_int(cur.token(), v)) bad("expected an integer");
            if (*type == AttrType::Int32 && (v < std::numeric_limits<int32_t>::min() || v > std::numeric_limits<int32_t>::max())) {
                bad("an int past the 32-bit range");
            }
            end_of_value();
            if (*type == AttrType::Int32) cs.add<int32_t>(Domain::Detail, name)[0] = static_cast<int32_t>(v);
            else cs.add<int64_t>(Domain::Detail, name)[0] = v;
            break;
        }
        case AttrType::Float3: {
            float3 v;
            for (int k = 0; k < 3; ++k)
                if (!parse_float(cur.token(), v[k]) || !std::isfinite(v[k])) bad("expected three finite floats");
            end_of_value();
            cs.add<float3>(Domain::Detail, name)[0] = v;
            break;
        }
    }
}

}  // namespace groom::io
