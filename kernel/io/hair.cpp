// Cem Yuksel's .hair format (http://www.cemyuksel.com/research/hairmodels/), little-endian:
// a 128-byte header ("HAIR", u32 strands, u32 points, u32 flags, u32 default segments,
// f32 default thickness, f32 default transparency, f32 default colour[3], 88 bytes of text), then
// the arrays the flags announce: u16 segments per strand (1), f32 xyz points (2), f32 thickness per
// point (4), f32 transparency per point (8), f32 rgb colour per point (16).
// Mapping: thickness <-> point `width`, colour <-> point float3 `Cd`, transparency <-> point
// `opacity` = 1 - transparency. Other attributes have no place in the format.
#include "kernel/io/formats.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <ostream>
#include <sstream>

namespace groom::io {

namespace {

constexpr size_t kHeader = 128;
constexpr uint32_t kSegments = 1, kPoints = 2, kThickness = 4, kTransparency = 8, kColor = 16;

template <class T> T get(const std::string& d, size_t at)
{
    T v;
    std::memcpy(&v, d.data() + at, sizeof v);
    if constexpr (std::endian::native == std::endian::big) {
        char b[sizeof v];
        std::memcpy(b, &v, sizeof v);
        std::reverse(b, b + sizeof v);
        std::memcpy(&v, b, sizeof v);
    }
    return v;
}

template <class T> void put(std::string& out, T v)
{
    char b[sizeof v];
    std::memcpy(b, &v, sizeof v);
    if constexpr (std::endian::native == std::endian::big) std::reverse(b, b + sizeof v);
    out.append(b, sizeof v);
}

}  // namespace

CurveSet read_hair(const FileBytes& file)
{
    const std::string& d = file.data;
    if (d.size() < kHeader) fail_at_byte(file.name, d.size(), "truncated: expected a 128-byte .hair header, found " + std::to_string(d.size()) + " bytes");
    if (d.compare(0, 4, "HAIR") != 0) fail_at_byte(file.name, 0, "expected the 'HAIR' signature, found " + describe_found(d.substr(0, 4)));
    const uint32_t strands = get<uint32_t>(d, 4), points = get<uint32_t>(d, 8), flags = get<uint32_t>(d, 12);
    const uint32_t default_segments = get<uint32_t>(d, 16);
    const float default_thickness = get<float>(d, 20), default_transparency = get<float>(d, 24);
    const float3 default_color{get<float>(d, 28), get<float>(d, 32), get<float>(d, 36)};
    if (!(flags & kPoints)) fail_at_byte(file.name, 12, "flags " + std::to_string(flags) + " announce no point array (bit 2): nothing to read");

    // Every announced array must fit in the file: checked before allocating anything.
    const uint64_t need = uint64_t(flags & kSegments ? 2 : 0) * strands +
                          uint64_t(12 + (flags & kThickness ? 4 : 0) + (flags & kTransparency ? 4 : 0) + (flags & kColor ? 12 : 0)) * points;
    if (need > d.size() - kHeader) {
        throw LimitExceeded(file.name + ": byte 128: header claims " + std::to_string(strands) + " strands and " + std::to_string(points) +
                            " points (flags " + std::to_string(flags) + "), which need " + std::to_string(need) + " bytes after the header, but only " +
                            std::to_string(d.size() - kHeader) + " follow; the file is truncated or corrupt");
    }

    // Every strand has at least one point, so more strands than points is corrupt. Without a segment
    // array (flags bit 1) nothing above bounds `strands`: check it before allocating per strand.
    if (strands > points) {
        throw LimitExceeded(file.name + ": byte 4: header claims " + std::to_string(strands) + " strands but only " +
                            std::to_string(points) + " points; every strand has at least one point");
    }
    std::vector<int64_t> counts(strands);
    size_t at = kHeader;
    int64_t total = 0;
    for (uint32_t s = 0; s < strands; ++s) {
        const uint32_t segs = flags & kSegments ? get<uint16_t>(d, at + 2 * s) : default_segments;
        counts[s] = int64_t(segs) + 1;
        total += counts[s];
    }
    if (flags & kSegments) at += 2 * size_t(strands);
    if (total != points) {
        fail_at_byte(file.name, flags & kSegments ? kHeader : 16,
                     "strand segment counts add up to " + std::to_string(total) + " points but the header says " + std::to_string(points));
    }
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    for (uint32_t i = 0; i < points; ++i, at += 12) {
        P[i] = {get<float>(d, at), get<float>(d, at + 4), get<float>(d, at + 8)};
        if (!isfinite(P[i])) fail_at_byte(file.name, at, "point " + std::to_string(i) + " is not finite (NaN or inf)");
    }
    if (flags & kThickness) {
        auto w = cs.add<float>(Domain::Point, attr::width);
        for (uint32_t i = 0; i < points; ++i, at += 4) w[i] = get<float>(d, at);
    }
    else if (default_thickness > 0) {
        auto w = cs.add<float>(Domain::Point, attr::width);
        std::fill(w.begin(), w.end(), default_thickness);
    }
    if (flags & kTransparency) {
        auto o = cs.add<float>(Domain::Point, "opacity");
        for (uint32_t i = 0; i < points; ++i, at += 4) o[i] = 1.0f - get<float>(d, at);
    }
    else if (default_transparency > 0) {
        auto o = cs.add<float>(Domain::Point, "opacity");
        std::fill(o.begin(), o.end(), 1.0f - default_transparency);
    }
    if (flags & kColor) {
        auto c = cs.add<float3>(Domain::Point, "Cd");
        for (uint32_t i = 0; i < points; ++i, at += 12) c[i] = {get<float>(d, at), get<float>(d, at + 4), get<float>(d, at + 8)};
    }
    (void)default_color;  // a uniform default colour is not turned into a column: it is not per-point data
    return cs;
}

void write_hair(const CurveSet& curves, std::ostream& stream)
{
    if (curves.num_curves() > UINT32_MAX || curves.num_points() > UINT32_MAX) throw InvalidParam("hair: more than 2^32 strands or points");
    for (size_t c = 0; c < curves.num_curves(); ++c) {
        const int64_t n = curves.points_in(c);
        if (n < 1 || n > 65536) {
            throw InvalidParam("hair: curve " + std::to_string(c) + " has " + std::to_string(n) +
                               " points; .hair stores 1 to 65536 points per strand (u16 segment count)");
        }
    }
    const auto width = curves.find<float>(Domain::Point, attr::width);
    const auto opacity = curves.find<float>(Domain::Point, "opacity");
    const auto color = curves.find<float3>(Domain::Point, "Cd");
    const uint32_t flags = kSegments | kPoints | (width.empty() ? 0 : kThickness) | (opacity.empty() ? 0 : kTransparency) | (color.empty() ? 0 : kColor);
    // Written a block at a time straight to the stream: the whole file as one string first was a
    // copy of the output held beside the curves (issue 17: a million hairs' curl peaked at 1.8 GB
    // against 0.5 GB written).
    std::string out;
    auto flush = [&](bool force) {
        if (!force && out.size() < (size_t(1) << 20)) return;
        stream.write(out.data(), std::streamsize(out.size()));
        out.clear();
    };
    out += "HAIR";
    put<uint32_t>(out, static_cast<uint32_t>(curves.num_curves()));
    put<uint32_t>(out, static_cast<uint32_t>(curves.num_points()));
    put<uint32_t>(out, flags);
    put<uint32_t>(out, 0);       // default segments: unused, every strand has its own count
    put<float>(out, 0.0f);       // default thickness: 0 = none given (read back without a width)
    put<float>(out, 0.0f);       // default transparency
    for (int k = 0; k < 3; ++k) put<float>(out, 1.0f);  // default colour
    std::string info = "groom " GROOM_VERSION;
    info.resize(88, '\0');
    out += info;
    for (size_t c = 0; c < curves.num_curves(); ++c) {
        put<uint16_t>(out, static_cast<uint16_t>(curves.points_in(c) - 1));
        flush(false);
    }
    // The columns as they lie in memory on a little-endian machine: one write each, not a call
    // per number (write_hair was 4x the read of the same file).
    auto column = [&](const auto& values, auto each) {
        if constexpr (std::endian::native == std::endian::little) {
            flush(true);
            stream.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size_bytes()));
        }
        else {
            for (const auto& v : values) each(v), flush(false);
        }
    };
    static_assert(sizeof(float3) == 3 * sizeof(float));
    column(curves.positions(), [&](const float3& p) { put(out, p.x), put(out, p.y), put(out, p.z); });
    column(width, [&](float w) { put(out, w); });
    for (float o : opacity) put(out, 1.0f - o), flush(false);
    for (const float3& c : color) put(out, c.x), put(out, c.y), put(out, c.z), flush(false);
    flush(true);
}

std::string write_hair(const CurveSet& curves)
{
    std::ostringstream s;
    write_hair(curves, s);
    return std::move(s).str();
}

}  // namespace groom::io
