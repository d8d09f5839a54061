#include "ops/select.h"

#include "kernel/curve_set_edit.h"
#include "kernel/error.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string>
#include <utility>
#include <variant>

namespace groom {

namespace {

std::string quoted(std::string_view s) { return "'" + std::string(s) + "'"; }

bool parse_int(std::string_view s, int64_t& v)
{
    if (s.empty()) return false;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && end == s.data() + s.size();
}

bool parse_number(std::string_view s, double& v)
{
    if (s.empty()) return false;
    // from_chars for double takes no leading '+'; accept one as people write it.
    if (s.front() == '+') s.remove_prefix(1);
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && end == s.data() + s.size() && std::isfinite(v);
}

std::string_view trim(std::string_view s)
{
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

bool compare(double a, CompareOp op, double b)
{
    switch (op) {
        case CompareOp::Less: return a < b;
        case CompareOp::LessEqual: return a <= b;
        case CompareOp::Greater: return a > b;
        case CompareOp::GreaterEqual: return a >= b;
        case CompareOp::Equal: return a == b;
        case CompareOp::NotEqual: return a != b;
    }
    return false;
}

std::string attribute_names(const CurveSet& cs)
{
    std::string names;
    for (Domain d : {Domain::Curve, Domain::Point, Domain::Detail})
        for (const Attribute& a : cs.attributes(d).all()) names += (names.empty() ? "" : ", ") + a.name + " (" + domain_name(d) + ")";
    return names.empty() ? "none" : names;
}

/// Per-curve values of one `where` test's attribute, as doubles.
std::vector<double> test_values(const CurveSet& src, const AttributeTest& t)
{
    const Attribute* a = nullptr;
    Domain domain = Domain::Curve;
    for (Domain d : {Domain::Curve, Domain::Point, Domain::Detail}) {
        if ((a = src.attributes(d).find(t.name))) {
            domain = d;
            break;
        }
    }
    if (!a && t.name == attr::id && t.component < 0) {
        // Curves without ids are identified by their index (CurveSet::curve_ids), here as in `ids`.
        const std::vector<int64_t> ids = src.curve_ids();
        return std::vector<double>(ids.begin(), ids.end());
    }
    if (!a) {
        throw InvalidParam("select: `where` names attribute '" + t.name + "', which the curves do not have (they have: " +
                           attribute_names(src) + ")");
    }
    if (a->type() == AttrType::String) throw InvalidParam("select: `where` attribute '" + t.name + "' holds strings; expected numbers");
    if (a->type() == AttrType::Float3 && t.component < 0) {
        throw InvalidParam("select: `where` attribute '" + t.name + "' holds float3 values; name a component ('" + t.name + ".x', .y or .z)");
    }
    if (a->type() != AttrType::Float3 && t.component >= 0) {
        throw InvalidParam("select: `where` attribute '" + t.name + "' holds " + type_name(a->type()) + " values, which have no components");
    }
    const size_t nc = src.num_curves();
    std::vector<double> out(nc);
    auto element = [&](size_t c) -> size_t {
        if (domain == Domain::Curve) return c;
        if (domain == Domain::Point) return size_t(src.points_of(c).begin);
        return 0;
    };
    std::visit(
        [&](const auto& v) {
            using T = typename std::decay_t<decltype(v)>::value_type;
            if constexpr (!std::is_same_v<T, std::string>) {
                for (size_t c = 0; c < nc; ++c) {
                    // A point attribute of a curve without points has no root to read: never matches.
                    if (domain == Domain::Point && src.points_in(c) == 0) {
                        out[c] = NAN;
                        continue;
                    }
                    const T& x = v[element(c)];
                    if constexpr (std::is_same_v<T, float3>) out[c] = double(x[t.component]);
                    else out[c] = double(x);
                }
            }
        },
        a->data);
    return out;
}

/// The curve's prim path for every curve, from curve attribute `prim` and detail `prim_paths`.
std::vector<std::string_view> prim_paths(const CurveSet& src, std::vector<std::string>& table)
{
    const Attribute* idx = src.attributes(Domain::Curve).find("prim");
    const std::string lines = src.detail_string("prim_paths");
    if (!idx || (idx->type() != AttrType::Int32 && idx->type() != AttrType::Int64) || lines.empty()) {
        throw InvalidParam("select: `prim` needs curves that carry their prim paths (an int curve attribute 'prim' indexing "
                           "the lines of the detail string 'prim_paths'); these curves have none");
    }
    for (size_t pos = 0; pos <= lines.size();) {
        const size_t nl = std::min(lines.find('\n', pos), lines.size());
        table.emplace_back(lines.substr(pos, nl - pos));
        pos = nl + 1;
    }
    std::vector<std::string_view> out(src.num_curves());
    for (size_t c = 0; c < out.size(); ++c) {
        const int64_t i = idx->type() == AttrType::Int32 ? int64_t(idx->values<int32_t>()[c]) : idx->values<int64_t>()[c];
        if (i < 0 || i >= int64_t(table.size())) {
            throw InvalidGeometry("select: curve " + std::to_string(c) + " has prim index " + std::to_string(i) + ", out of range (" +
                                  std::to_string(table.size()) + " prim paths)");
        }
        out[c] = table[size_t(i)];
    }
    return out;
}

/// `path` is `prim` or lies under it (`/A/B` is under `/A`, `/AB` is not).
bool under(std::string_view path, std::string_view prim)
{
    while (prim.size() > 1 && prim.back() == '/') prim.remove_suffix(1);
    if (path.substr(0, prim.size()) != prim) return false;
    return path.size() == prim.size() || path[prim.size()] == '/' || prim == "/";
}

}  // namespace

AttributeTest parse_attribute_test(std::string_view text, std::string_view option)
{
    const std::string opt(option);
    auto fail = [&](const std::string& why) -> AttributeTest {
        throw InvalidParam("select: `" + opt + "` " + quoted(text) + ": " + why +
                           "; expected NAME OP NUMBER with OP one of < <= > >= == != (e.g. 'width>0.01', 'kind==2', 'Cd.x<=0.5')");
    };
    const std::string_view s = trim(text);
    const size_t at = s.find_first_of("<>=!");
    if (at == std::string_view::npos) return fail("no comparison operator");
    std::string_view name = trim(s.substr(0, at));
    const size_t op_end = std::min(s.find_first_not_of("<>=!", at), s.size());
    const std::string_view op_text = s.substr(at, op_end - at);
    std::string_view rest = s.substr(op_end);
    AttributeTest t;
    static constexpr std::pair<std::string_view, CompareOp> ops[] = {
        {"<=", CompareOp::LessEqual}, {">=", CompareOp::GreaterEqual}, {"==", CompareOp::Equal}, {"!=", CompareOp::NotEqual},
        {"<", CompareOp::Less},       {">", CompareOp::Greater},       {"=", CompareOp::Equal},
    };
    bool found = false;
    for (const auto& [tok, op] : ops) {
        if (op_text == tok) {
            t.op = op;
            found = true;
            break;
        }
    }
    if (!found) return fail("unknown operator " + quoted(op_text));
    if (name.empty()) return fail("no attribute name before the operator");
    if (name.size() > 2 && name[name.size() - 2] == '.') {
        const char c = name.back();
        if (c < 'x' || c > 'z') return fail("component " + quoted(name.substr(name.size() - 2)) + " is not .x, .y or .z");
        t.component = c - 'x';
        name.remove_suffix(2);
    }
    for (char c : name) {
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':')) return fail("attribute name " + quoted(name) + " has " + quoted(std::string(1, c)));
    }
    t.name = std::string(name);
    if (!parse_number(trim(rest), t.value)) return fail("the value " + quoted(trim(rest)) + " is not a finite number");
    return t;
}

std::vector<IdRange> parse_id_ranges(std::string_view text, std::string_view option)
{
    const std::string opt(option);
    std::vector<IdRange> out;
    size_t pos = 0;
    while (pos <= text.size()) {
        const size_t comma = std::min(text.find(',', pos), text.size());
        const std::string_view item = trim(text.substr(pos, comma - pos));
        auto fail = [&](const std::string& why) {
            throw InvalidParam("select: `" + opt + "` " + quoted(text) + ": " + why +
                               "; expected a comma-separated list of ids and inclusive ranges A-B (e.g. '0-9,20,30-39')");
        };
        if (item.empty()) fail("an empty entry");
        // The range dash is the first '-' that is not a sign (a sign starts the item or follows a dash).
        size_t dash = std::string_view::npos;
        for (size_t i = 1; i < item.size(); ++i) {
            if (item[i] == '-' && item[i - 1] != '-') {
                dash = i;
                break;
            }
        }
        IdRange r;
        if (dash == std::string_view::npos) {
            if (!parse_int(item, r.lo)) fail(quoted(item) + " is not an integer id");
            r.hi = r.lo;
        }
        else {
            if (!parse_int(trim(item.substr(0, dash)), r.lo) || !parse_int(trim(item.substr(dash + 1)), r.hi)) {
                fail(quoted(item) + " is not a range of two integer ids");
            }
            if (r.lo > r.hi) fail("range " + quoted(item) + " ends before it starts");
        }
        out.push_back(r);
        pos = comma + 1;
    }
    return out;
}

void SelectParams::validate() const
{
    if (ids.empty() && guides.empty() && where.empty() && prims.empty()) {
        throw InvalidParam("select: nothing to select by; give `ids`, `guide`, `where` or `prim`");
    }
    for (const IdRange& r : ids) {
        if (r.lo > r.hi) {
            throw InvalidParam("select: `ids` range " + std::to_string(r.lo) + "-" + std::to_string(r.hi) + " ends before it starts");
        }
    }
    for (const std::string& p : prims) {
        if (p.empty() || p.front() != '/') throw InvalidParam("select: `prim` '" + p + "' is not an absolute prim path (expected /Name/...)");
    }
}

CurveSet select(const CurveSet& src, const SelectParams& params, SelectStats* stats)
{
    params.validate();
    const size_t nc = src.num_curves();
    std::vector<char> match(nc, 1);

    if (!params.ids.empty()) {
        const std::vector<int64_t> ids = src.curve_ids();
        for (size_t c = 0; c < nc; ++c) {
            const int64_t id = ids[c];
            match[c] &= char(std::any_of(params.ids.begin(), params.ids.end(), [&](const IdRange& r) { return id >= r.lo && id <= r.hi; }));
        }
    }
    if (!params.guides.empty()) {
        const Attribute* g = src.attributes(Domain::Curve).find("guide");
        if (!g || (g->type() != AttrType::Int32 && g->type() != AttrType::Int64)) {
            throw InvalidParam("select: `guide` needs an int curve attribute 'guide' (written by generate, partition, sections...); "
                               "these curves have " + std::string(g ? "one of type " + std::string(type_name(g->type())) : "none"));
        }
        for (size_t c = 0; c < nc; ++c) {
            const int64_t v = g->type() == AttrType::Int32 ? int64_t(g->values<int32_t>()[c]) : g->values<int64_t>()[c];
            match[c] &= char(std::find(params.guides.begin(), params.guides.end(), v) != params.guides.end());
        }
    }
    for (const AttributeTest& t : params.where) {
        const std::vector<double> v = test_values(src, t);
        for (size_t c = 0; c < nc; ++c) match[c] &= char(compare(v[c], t.op, t.value));
    }
    if (!params.prims.empty()) {
        std::vector<std::string> table;
        const std::vector<std::string_view> paths = prim_paths(src, table);
        for (size_t c = 0; c < nc; ++c) {
            match[c] &= char(std::any_of(params.prims.begin(), params.prims.end(), [&](const std::string& p) { return under(paths[c], p); }));
        }
    }

    std::vector<char> remove(nc);
    int64_t matched = 0;
    for (size_t c = 0; c < nc; ++c) {
        matched += match[c];
        remove[c] = char(params.invert ? match[c] : !match[c]);
    }
    CurveSet out = remove_curves(src, remove);
    if (stats) {
        stats->matched = matched;
        stats->kept = int64_t(out.num_curves());
    }
    return out;
}

}  // namespace groom
