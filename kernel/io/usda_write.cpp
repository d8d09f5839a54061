// The .usda writer: one linear BasisCurves prim holding every curve, point widths and one primvar
// per attribute (../shared/NOTES.md: always write `type`). Shares only identifier rules with the
// reader (usda_lexer.h), so it is kept apart from the parsing files.
#include "kernel/curve_set_edit.h"
#include "kernel/io/formats.h"
#include "kernel/io/usda_lexer.h"
#include "kernel/units.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <ostream>

namespace groom::io {

namespace {

using usda::ident_start;

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
void append_array(std::string& out, std::span<const T> values, std::span<const int64_t> breaks, const char* indent, const TextSpill* spill = nullptr)
{
    out += "[";
    size_t next_break = 1;
    for (size_t i = 0; i < values.size(); ++i) {
        if (spill && (i & 4095) == 0) (*spill)();
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

namespace {

std::string write_usda_text(const CurveSet& curves, bool closed, std::ostream* to);

}  // namespace

std::string write_usda(const CurveSet& curves, bool closed)
{
    // Closed loops are written periodic, each point once (read back, the first point is repeated
    // at the end again): `groom convert` of a hairline had written it open, its ends on top of
    // each other (a trial).
    if (closed || is_closed(curves)) return write_usda_text(without_closing_points(curves), true, nullptr);
    return write_usda_text(curves, false, nullptr);
}

void stream_usda(const CurveSet& curves, bool closed, std::ostream& to)
{
    const std::string rest = closed || is_closed(curves) ? write_usda_text(without_closing_points(curves), true, &to)
                                                         : write_usda_text(curves, false, &to);
    to.write(rest.data(), static_cast<std::streamsize>(rest.size()));
}

namespace {

/// The file's text; with `to`, all but the returned tail is written there as it is made.
std::string write_usda_text(const CurveSet& curves, bool closed, std::ostream* to)
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
    out.reserve(to ? (size_t(5) << 20) : curves.num_points() * 40 + curves.num_curves() * 6 + 1024);
    const TextSpill spill{out, to};
    // Layer metadata from the detail strings `groom transform` sets: the up axis (Y unless the curves
    // say Z) and the unit, which USD gives as metres per unit.
    const std::string up = curves.detail_string("up_axis") == "Z" ? "Z" : "Y";
    out += "#usda 1.0\n(\n    defaultPrim = \"groom\"\n    doc = \"Written by groom " GROOM_VERSION "\"\n";
    const std::string units = curves.detail_string("units");
    const double mpu = meters_per_unit(units);
    if (mpu > 0) {
        out += "    metersPerUnit = ";
        append_number(out, float(mpu));
        out += "\n";
    }
    out += "    upAxis = \"" + up + "\"\n)\n\n";
    out += "def BasisCurves \"groom\"\n{\n";
    out += "    uniform token type = \"linear\"\n";
    // Periodic: USD's way to say a curve is closed (UsdGeomBasisCurves; a linear one joins its last
    // point to its first), so a DCC shows a hairline as the loop it is.
    out += closed ? "    uniform token wrap = \"periodic\"\n" : "    uniform token wrap = \"nonperiodic\"\n";
    std::vector<int32_t> counts(curves.num_curves());
    for (size_t c = 0; c < counts.size(); ++c) {
        const int64_t n = curves.points_in(c);
        if (n > INT32_MAX) throw InvalidParam("usda: curve " + std::to_string(c) + " has more than 2^31 points");
        counts[c] = static_cast<int32_t>(n);
    }
    out += "    int[] curveVertexCounts = ";
    append_array<int32_t>(out, counts, {}, "        ", &spill);
    out += "\n    point3f[] points = ";
    append_array<float3>(out, curves.positions(), curves.offsets(), "        ", &spill);
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
        append_array<float>(out, width, curves.offsets(), "        ", &spill);
        out += " (\n        interpolation = \"vertex\"\n    )\n";
    }
    for (Domain d : {Domain::Point, Domain::Curve, Domain::Detail}) {
        const char* interp = d == Domain::Point ? "vertex" : d == Domain::Curve ? "uniform" : "constant";
        for (const Attribute& a : curves.attributes(d).all()) {
            if (d == Domain::Point && (a.name == attr::P || (a.name == attr::width && a.type() == AttrType::Float))) continue;
            // Said by the layer's upAxis and metersPerUnit, and read back from there.
            // (Y is USD's default and the layer's when nothing is said: an up_axis Y is kept as a primvar.)
            if (d == Domain::Detail && ((a.name == "up_axis" && up == "Z") || (a.name == "units" && mpu > 0))) {
                continue;
            }
            out += "    ";
            out += usd_scalar_type(a.type());
            if (d != Domain::Detail) out += "[]";
            out += " primvars:" + a.name + " = ";
            std::visit(
                [&](const auto& v) {
                    using T = typename std::decay_t<decltype(v)>::value_type;
                    if (d == Domain::Detail) append_value(out, v[0]);
                    else append_array<T>(out, v, d == Domain::Point ? curves.offsets() : std::span<const int64_t>(), "        ", &spill);
                },
                a.data);
            out += " (\n        interpolation = \"";
            out += interp;
            out += "\"\n    )\n";
        }
    }
    // Each root's scalp UV (ops/root_uv.h) also as USD's texture coordinates, where renderers and
    // engine importers look for them; root_uv itself stays above so groom reads it back.
    if (const auto uv = curves.find<float3>(Domain::Curve, "root_uv"); !uv.empty() && !curves.attributes(Domain::Point).find("st") &&
                                                                       !curves.attributes(Domain::Curve).find("st") &&
                                                                       !curves.attributes(Domain::Detail).find("st")) {
        out += "    texCoord2f[] primvars:st = [";
        for (size_t c = 0; c < uv.size(); ++c) {
            if ((c & 4095) == 0) spill();
            if (c > 0) out += c % 8 == 0 ? ",\n        " : ", ";
            out += '(';
            append_number(out, uv[c].x);
            out += ", ";
            append_number(out, uv[c].y);
            out += ')';
        }
        out += "] (\n        interpolation = \"uniform\"\n    )\n";
    }
    out += "}\n";
    return out;
}

}  // namespace

}  // namespace groom::io
