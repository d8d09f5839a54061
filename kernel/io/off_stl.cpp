// OFF (Object File Format, ASCII) and STL (ASCII and binary) meshes. STL stores each triangle with
// its own three corners: the soup keeps them as they are (3 vertices per face); mesh_stats and the
// repair in fields/ weld them.
#include "kernel/io/formats.h"

#include <bit>
#include <cstring>

namespace groom::io {

namespace {

std::string_view next_token(TextCursor& cur)
{
    // Tokens across lines, skipping '#' comments.
    for (;;) {
        if (cur.at_line_end(true)) {
            if (!cur.next_line()) return {};
            continue;
        }
        return cur.token();
    }
}

}  // namespace

PolygonSoup read_off(const FileBytes& file)
{
    TextCursor cur(file.data);
    std::string_view magic = next_token(cur);
    // OFF, COFF, NOFF, CNOFF, STOFF ...: extra per-vertex values are skipped with the rest of the line.
    if (magic.size() < 3 || magic.substr(magic.size() - 3) != "OFF") {
        fail_at_line(file.name, cur.line(), "expected the 'OFF' keyword, found " + describe_found(magic));
    }
    if (!cur.at_line_end() && cur.token() == "BINARY") fail_at_line(file.name, cur.line(), "binary OFF is not supported (expected ASCII OFF)");
    int64_t counts[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
        const std::string_view t = next_token(cur);
        if (!parse_int(t, counts[k]) || counts[k] < 0) {
            fail_at_line(file.name, cur.line(), std::string("expected the ") + (k == 0 ? "vertex" : k == 1 ? "face" : "edge") + " count, found " + describe_found(t));
        }
    }
    // Each vertex needs at least "0 0 0\n" and each face "3 0 0 0\n" worth of bytes.
    check_claimed_count(file.name, "vertices", counts[0], 6, file.data.size() - cur.offset(), cur.offset());
    check_claimed_count(file.name, "faces", counts[1], 2, file.data.size() - cur.offset(), cur.offset());
    if (counts[0] > INT32_MAX) throw LimitExceeded(file.name + ": more than 2^31 vertices");
    PolygonSoup soup;
    soup.points.resize(counts[0]);
    for (int64_t i = 0; i < counts[0]; ++i) {
        cur.next_line();
        float3 p;
        for (int k = 0; k < 3; ++k) {
            const std::string_view t = next_token(cur);
            if (!parse_float(t, p[k])) fail_at_line(file.name, cur.line(), "expected vertex " + std::to_string(i) + " coordinates, found " + (t.empty() ? std::string("end of file") : describe_found(t)));
        }
        if (!isfinite(p)) fail_at_line(file.name, cur.line(), "vertex coordinate is not finite (NaN, inf, or past float's range of 3.4e38)");
        soup.points[i] = p;
    }
    std::vector<int32_t> face;
    for (int64_t f = 0; f < counts[1]; ++f) {
        cur.next_line();
        const std::string_view t = next_token(cur);
        int64_t n = 0;
        if (!parse_int(t, n) || n < 1) fail_at_line(file.name, cur.line(), "expected face " + std::to_string(f) + "'s vertex count, found " + (t.empty() ? std::string("end of file") : describe_found(t)));
        face.clear();
        for (int64_t k = 0; k < n; ++k) {
            const std::string_view it = cur.token();
            int64_t i = 0;
            if (!parse_int(it, i)) fail_at_line(file.name, cur.line(), "expected " + std::to_string(n) + " vertex indices, found " + describe_found(it));
            if (i < 0 || i >= counts[0]) fail_at_line(file.name, cur.line(), "vertex index " + std::to_string(i) + " out of range (" + std::to_string(counts[0]) + " vertices)");
            face.push_back(static_cast<int32_t>(i));
        }
        soup.add_face(face);
    }
    return soup;
}

PolygonSoup read_stl(const FileBytes& file)
{
    const std::string& d = file.data;
    PolygonSoup soup;
    uint32_t tris = 0;
    if (d.size() >= 84) std::memcpy(&tris, d.data() + 80, 4);
    if constexpr (std::endian::native == std::endian::big) tris = __builtin_bswap32(tris);
    // Some binary exporters also start their header with "solid": ASCII only if a facet (or the end) follows.
    bool ascii = false;
    if (d.compare(0, 5, "solid") == 0 && d.find('\n') != std::string::npos) {
        const size_t next = d.find_first_not_of(" \t\r\n", d.find('\n'));
        ascii = next != std::string::npos && (d.compare(next, 5, "facet") == 0 || d.compare(next, 8, "endsolid") == 0);
    }
    if (!ascii) {
        if (d.size() < 84) fail_at_byte(file.name, d.size(), "truncated: expected an 84-byte binary STL header, found " + std::to_string(d.size()) + " bytes");
        // The exact size check also refuses absurd counts before anything is allocated.
        if (84 + 50 * uint64_t(tris) != d.size()) {
            fail_at_byte(file.name, 80, "binary STL claims " + std::to_string(tris) + " triangles (" + std::to_string(84 + 50 * uint64_t(tris)) +
                                            " bytes) but the file has " + std::to_string(d.size()) + " bytes");
        }
        soup.points.reserve(3 * size_t(tris));
        int32_t corner[3];
        for (uint32_t t = 0; t < tris; ++t) {
            const size_t at = 84 + 50 * size_t(t) + 12;  // skip the facet normal
            for (int v = 0; v < 3; ++v) {
                float xyz[3];
                std::memcpy(xyz, d.data() + at + 12 * v, 12);
                if constexpr (std::endian::native == std::endian::big)
                    for (float& f : xyz) f = std::bit_cast<float>(__builtin_bswap32(std::bit_cast<uint32_t>(f)));
                const float3 p{xyz[0], xyz[1], xyz[2]};
                if (!isfinite(p)) fail_at_byte(file.name, at + 12 * v, "triangle " + std::to_string(t) + " has a non-finite vertex");
                corner[v] = static_cast<int32_t>(soup.points.size());
                soup.points.push_back(p);
            }
            soup.add_face(corner);
        }
        return soup;
    }
    TextCursor cur(d);
    auto expect = [&](std::string_view word) {
        const std::string_view t = next_token(cur);
        if (t != word) fail_at_line(file.name, cur.line(), "expected '" + std::string(word) + "', found " + (t.empty() ? std::string("end of file") : describe_found(t)));
    };
    expect("solid");
    cur.rest_of_line();  // the solid's name
    std::vector<int32_t> face;
    for (;;) {
        const std::string_view t = next_token(cur);
        if (t == "endsolid") break;
        if (t != "facet") fail_at_line(file.name, cur.line(), "expected 'facet' or 'endsolid', found " + (t.empty() ? std::string("end of file") : describe_found(t)));
        cur.rest_of_line();  // normal nx ny nz
        expect("outer");
        expect("loop");
        face.clear();
        for (;;) {
            const std::string_view v = next_token(cur);
            if (v == "endloop") break;
            if (v != "vertex") fail_at_line(file.name, cur.line(), "expected 'vertex' or 'endloop', found " + (v.empty() ? std::string("end of file") : describe_found(v)));
            float3 p;
            for (int k = 0; k < 3; ++k) {
                const std::string_view c = cur.token();
                if (!parse_float(c, p[k])) fail_at_line(file.name, cur.line(), "expected 3 vertex coordinates, found " + describe_found(c));
            }
            if (!isfinite(p)) fail_at_line(file.name, cur.line(), "vertex coordinate is not finite (NaN, inf, or past float's range of 3.4e38)");
            face.push_back(static_cast<int32_t>(soup.points.size()));
            soup.points.push_back(p);
        }
        if (face.size() < 3) fail_at_line(file.name, cur.line(), "expected at least 3 vertices in a facet, found " + std::to_string(face.size()));
        soup.add_face(face);
        expect("endfacet");
    }
    return soup;
}

}  // namespace groom::io
