// What every reader fuzz target checks, whatever the format: a reader given arbitrary bytes either
// returns valid geometry or throws a groom::Error (ParseError, LimitExceeded, ...) with a message.
// Anything else (a crash, an out-of-bounds access, undefined behaviour, a std::exception that is not
// ours, a hang, an allocation bigger than libFuzzer's -malloc_limit_mb) is a bug and ends the run.
// What we read we must be able to write again, and what we write we must read back identically.
#pragma once

#include "kernel/error.h"
#include "kernel/io/formats.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

namespace groom::fuzz {

inline io::FileBytes bytes_of(const uint8_t* data, size_t size, const char* name)
{
    return {name, std::string(reinterpret_cast<const char*>(data), size)};
}

/// Aborts (a libFuzzer crash with the input saved) when `ok` is false.
inline void require(bool ok)
{
    if (!ok) __builtin_trap();
}

inline bool same_positions(const CurveSet& a, const CurveSet& b)
{
    const auto pa = a.positions(), pb = b.positions();
    if (pa.size() != pb.size()) return false;
    for (size_t i = 0; i < pa.size(); ++i)
        if (!(pa[i].x == pb[i].x && pa[i].y == pb[i].y && pa[i].z == pb[i].z)) return false;
    return true;
}

/// read -> validate -> write -> read again, comparing positions bit for bit (OBJ drops empty
/// curves, so only positions and the point count are compared, not the curve count).
template <class Read, class Write>
void check_curve_reader(const uint8_t* data, size_t size, const char* name, Read read, Write write)
{
    const io::FileBytes file = bytes_of(data, size, name);
    CurveSet cs;
    try {
        cs = read(file);
        cs.validate(file.name);
    }
    catch (const Error&) {
        return;  // a clean refusal
    }
    std::string written;
    try {
        written = write(cs);
    }
    catch (const Error&) {
        return;  // something the format cannot hold (e.g. an attribute name USD cannot spell): refused clearly
    }
    const CurveSet back = read(io::FileBytes{file.name, written});  // our own output must read back
    back.validate(file.name);
    require(same_positions(cs, back));
}

/// read -> every index in range and every point finite -> mesh statistics -> (optionally) write ->
/// read again with the same points and faces.
template <class Read, class Write>
void check_mesh_reader(const uint8_t* data, size_t size, const char* name, Read read, Write write)
{
    const io::FileBytes file = bytes_of(data, size, name);
    PolygonSoup soup;
    try {
        soup = read(file);
    }
    catch (const Error&) {
        return;
    }
    require(!soup.face_offsets.empty() && soup.face_offsets.front() == 0);
    require(soup.face_offsets.back() == static_cast<int64_t>(soup.face_indices.size()));
    for (size_t f = 0; f + 1 < soup.face_offsets.size(); ++f) require(soup.face_offsets[f] <= soup.face_offsets[f + 1]);
    for (int32_t i : soup.face_indices) require(i >= 0 && static_cast<size_t>(i) < soup.points.size());
    for (const float3& p : soup.points) require(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    // Texture coordinates: one per corner, each -1 (none) or a (u, v) pair of `uvs`.
    require(soup.uvs.size() % 2 == 0);
    if (soup.has_uvs()) {
        require(soup.face_uv_indices.size() == soup.face_indices.size());
        for (int32_t t : soup.face_uv_indices) require(t == -1 || (t >= 0 && static_cast<size_t>(t) < soup.uvs.size() / 2));
    }
    const MeshStats s = mesh_stats(soup);
    require(s.faces == static_cast<int64_t>(soup.num_faces()) && s.vertices == static_cast<int64_t>(soup.points.size()));
    if constexpr (!std::is_same_v<Write, std::nullptr_t>) {
        std::string written;
        try {
            written = write(soup);
        }
        catch (const Error&) {
            return;
        }
        const PolygonSoup back = read(io::FileBytes{file.name, written});
        require(back.points.size() == soup.points.size() && back.face_indices == soup.face_indices &&
                back.face_offsets == soup.face_offsets);
        for (size_t i = 0; i < soup.points.size(); ++i)
            require(back.points[i].x == soup.points[i].x && back.points[i].y == soup.points[i].y && back.points[i].z == soup.points[i].z);
    }
}

}  // namespace groom::fuzz
