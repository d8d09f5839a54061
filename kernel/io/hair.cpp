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
#include <cerrno>
#include <cstring>
#include <fstream>
#include <ostream>
#include <sstream>
#include <vector>

namespace groom::io {

namespace {

constexpr size_t kHeader = 128;
constexpr uint32_t kSegments = 1, kPoints = 2, kThickness = 4, kTransparency = 8, kColor = 16;

template <class T> void put(std::string& out, T v)
{
    char b[sizeof v];
    std::memcpy(b, &v, sizeof v);
    if constexpr (std::endian::native == std::endian::big) std::reverse(b, b + sizeof v);
    out.append(b, sizeof v);
}

}  // namespace

namespace {

/// Where read_hair takes its bytes: a file already in memory (stdin, a test), or a file on disk
/// read a stretch at a time straight into the curves' columns (reading it whole first held the
/// file beside its curves: twice a million hairs' 0.5 GB, issue 17).
class HairSource {
public:
    virtual ~HairSource() = default;
    virtual uint64_t size() const = 0;
    /// `n` bytes from `offset` (within size()), valid until the next call.
    virtual const char* bytes(uint64_t offset, size_t n) = 0;
};

class MemorySource final : public HairSource {
public:
    explicit MemorySource(const std::string& d) : d_(d) {}
    uint64_t size() const override { return d_.size(); }
    const char* bytes(uint64_t offset, size_t) override { return d_.data() + offset; }

private:
    const std::string& d_;
};

class FileSource final : public HairSource {
public:
    explicit FileSource(const std::string& path) : path_(path), f_(path, std::ios::binary)
    {
        if (!f_) throw IoError(path + ": cannot open for reading (" + std::strerror(errno) + ")");
        f_.seekg(0, std::ios::end);
        const std::streamoff size = f_.tellg();
        if (size < 0) throw IoError(path + ": cannot determine the file size (is it a directory?)");
        size_ = uint64_t(size);
    }
    uint64_t size() const override { return size_; }
    const char* bytes(uint64_t offset, size_t n) override
    {
        buffer_.resize(n);
        f_.seekg(std::streamoff(offset));
        if (n > 0 && !f_.read(buffer_.data(), std::streamsize(n))) throw IoError(path_ + ": read failed (" + std::strerror(errno) + ")");
        return buffer_.data();
    }

private:
    std::string path_;
    std::ifstream f_;
    uint64_t size_ = 0;
    std::vector<char> buffer_;
};

template <class T> T get_at(const char* p)
{
    T v;
    std::memcpy(&v, p, sizeof v);
    if constexpr (std::endian::native == std::endian::big) {
        char b[sizeof v];
        std::memcpy(b, &v, sizeof v);
        std::reverse(b, b + sizeof v);
        std::memcpy(&v, b, sizeof v);
    }
    return v;
}

/// Calls each(i, p) for the `count` records of `size` bytes from `at`, a stretch of the source at a time.
template <class Each> void for_each_record(HairSource& src, uint64_t at, uint64_t count, size_t size, Each each)
{
    constexpr uint64_t kStretch = uint64_t(1) << 18;  // records per read: 3 MB of points
    for (uint64_t i = 0; i < count; i += kStretch) {
        const uint64_t k = std::min(kStretch, count - i);
        const char* p = src.bytes(at + i * size, size_t(k * size));
        for (uint64_t j = 0; j < k; ++j) each(i + j, at + (i + j) * size, p + j * size);
    }
}

CurveSet read_hair_from(HairSource& src, const std::string& name)
{
    const uint64_t file_size = src.size();
    if (file_size < kHeader) fail_at_byte(name, file_size, "truncated: expected a 128-byte .hair header, found " + std::to_string(file_size) + " bytes");
    const std::string head(src.bytes(0, kHeader), kHeader);
    const char* h = head.data();
    if (head.compare(0, 4, "HAIR") != 0) fail_at_byte(name, 0, "expected the 'HAIR' signature, found " + describe_found(head.substr(0, 4)));
    const uint32_t strands = get_at<uint32_t>(h + 4), points = get_at<uint32_t>(h + 8), flags = get_at<uint32_t>(h + 12);
    const uint32_t default_segments = get_at<uint32_t>(h + 16);
    const float default_thickness = get_at<float>(h + 20), default_transparency = get_at<float>(h + 24);
    if (!(flags & kPoints)) fail_at_byte(name, 12, "flags " + std::to_string(flags) + " announce no point array (bit 2): nothing to read");

    // Every announced array must fit in the file: checked before allocating anything.
    const uint64_t need = uint64_t(flags & kSegments ? 2 : 0) * strands +
                          uint64_t(12 + (flags & kThickness ? 4 : 0) + (flags & kTransparency ? 4 : 0) + (flags & kColor ? 12 : 0)) * points;
    if (need > file_size - kHeader) {
        throw LimitExceeded(name + ": byte 128: header claims " + std::to_string(strands) + " strands and " + std::to_string(points) +
                            " points (flags " + std::to_string(flags) + "), which need " + std::to_string(need) + " bytes after the header, but only " +
                            std::to_string(file_size - kHeader) + " follow; the file is truncated or corrupt");
    }

    // Every strand has at least one point, so more strands than points is corrupt. Without a segment
    // array (flags bit 1) nothing above bounds `strands`: check it before allocating per strand.
    if (strands > points) {
        throw LimitExceeded(name + ": byte 4: header claims " + std::to_string(strands) + " strands but only " + std::to_string(points) +
                            " points; every strand has at least one point");
    }
    std::vector<int64_t> counts(strands);
    uint64_t at = kHeader;
    int64_t total = 0;
    if (flags & kSegments) {
        for_each_record(src, at, strands, 2, [&](uint64_t s, uint64_t, const char* p) { counts[s] = int64_t(get_at<uint16_t>(p)) + 1; });
        at += 2 * uint64_t(strands);
    }
    else {
        std::fill(counts.begin(), counts.end(), int64_t(default_segments) + 1);
    }
    for (const int64_t n : counts) total += n;
    if (total != points) {
        fail_at_byte(name, flags & kSegments ? kHeader : 16,
                     "strand segment counts add up to " + std::to_string(total) + " points but the header says " + std::to_string(points));
    }
    CurveSet cs = CurveSet::from_counts(counts);
    counts = {};
    auto P = cs.positions_for_write();
    for_each_record(src, at, points, 12, [&](uint64_t i, uint64_t byte, const char* p) {
        P[i] = {get_at<float>(p), get_at<float>(p + 4), get_at<float>(p + 8)};
        if (!isfinite(P[i])) fail_at_byte(name, byte, "point " + std::to_string(i) + " is not finite (NaN or inf)");
    });
    at += 12 * uint64_t(points);
    if (flags & kThickness) {
        auto w = cs.add<float>(Domain::Point, attr::width);
        for_each_record(src, at, points, 4, [&](uint64_t i, uint64_t, const char* p) { w[i] = get_at<float>(p); });
        at += 4 * uint64_t(points);
    }
    else if (default_thickness > 0) {
        auto w = cs.add<float>(Domain::Point, attr::width);
        std::fill(w.begin(), w.end(), default_thickness);
    }
    if (flags & kTransparency) {
        auto o = cs.add<float>(Domain::Point, "opacity");
        for_each_record(src, at, points, 4, [&](uint64_t i, uint64_t, const char* p) { o[i] = 1.0f - get_at<float>(p); });
        at += 4 * uint64_t(points);
    }
    else if (default_transparency > 0) {
        auto o = cs.add<float>(Domain::Point, "opacity");
        std::fill(o.begin(), o.end(), 1.0f - default_transparency);
    }
    if (flags & kColor) {
        auto c = cs.add<float3>(Domain::Point, "Cd");
        for_each_record(src, at, points, 12, [&](uint64_t i, uint64_t, const char* p) { c[i] = {get_at<float>(p), get_at<float>(p + 4), get_at<float>(p + 8)}; });
    }
    // A uniform default colour (header bytes 28-39) is not turned into a column: it is not per-point data.
    return cs;
}

}  // namespace

CurveSet read_hair(const FileBytes& file)
{
    MemorySource src(file.data);
    return read_hair_from(src, file.name);
}

CurveSet read_hair_file(const std::string& path)
{
    FileSource src(path);
    return read_hair_from(src, path);
}

HairBlockWriter::HairBlockWriter(std::ostream& stream, std::span<const int64_t> counts) : stream_(stream)
{
    // Places are counted from where the stream stands now (the start of a fresh file, in groom).
    const std::streamoff here = stream.tellp();
    base_ = here > 0 ? uint64_t(here) : 0;
    if (counts.size() > UINT32_MAX) throw InvalidParam("hair: more than 2^32 strands or points");
    segments_.resize(counts.size());
    for (size_t c = 0; c < counts.size(); ++c) {
        const int64_t n = counts[c];
        if (n < 1 || n > 65536) {
            throw InvalidParam("hair: curve " + std::to_string(c) + " has " + std::to_string(n) +
                               " points; .hair stores 1 to 65536 points per strand (u16 segment count)");
        }
        segments_[c] = static_cast<uint16_t>(n - 1);
        points_ += uint64_t(n);
    }
    if (points_ > UINT32_MAX) throw InvalidParam("hair: more than 2^32 strands or points");
}

void HairBlockWriter::put_at(uint64_t at, const char* bytes, size_t size)
{
    stream_.seekp(std::streamoff(base_ + at));
    stream_.write(bytes, std::streamsize(size));
}

template <class T, class Each> void HairBlockWriter::column(uint64_t at, std::span<const T> values, Each each)
{
    if constexpr (std::endian::native == std::endian::little) {
        // The values as they lie in memory: one write, not a call per number (write_hair was 4x
        // the read of the same file).
        put_at(at, reinterpret_cast<const char*>(values.data()), values.size_bytes());
    }
    else {
        std::string out;
        for (const T& v : values) each(out, v);
        put_at(at, out.data(), out.size());
    }
}

void HairBlockWriter::write(const CurveSet& block)
{
    if (curves_ + block.num_curves() > segments_.size()) {
        throw InvalidParam("hair: a block brings the strands written to " + std::to_string(curves_ + block.num_curves()) + " of " +
                           std::to_string(segments_.size()) + " announced");
    }
    for (size_t c = 0; c < block.num_curves(); ++c) {
        if (block.points_in(c) != int64_t(segments_[curves_ + c]) + 1) {
            throw InvalidParam("hair: strand " + std::to_string(curves_ + c) + " has " + std::to_string(block.points_in(c)) + " points; " +
                               std::to_string(int(segments_[curves_ + c]) + 1) + " were announced");
        }
    }
    if (block.num_curves() == 0) return;  // an empty block announces no columns
    const auto width = block.find<float>(Domain::Point, attr::width);
    const auto opacity = block.find<float>(Domain::Point, "opacity");
    const auto color = block.find<float3>(Domain::Point, "Cd");
    const uint32_t flags = kSegments | kPoints | (width.empty() ? 0 : kThickness) | (opacity.empty() ? 0 : kTransparency) | (color.empty() ? 0 : kColor);
    if (!started_) start(flags);
    else if (flags != flags_) {
        throw InvalidParam("hair: strand " + std::to_string(curves_) + " on has other point columns (flags " + std::to_string(flags) +
                           ") than the strands before it (" + std::to_string(flags_) + ")");
    }
    // Each array's part for this block at its place: the arrays follow one another, whole.
    const uint64_t n = points_, first = written_;
    uint64_t at = kHeader + 2 * uint64_t(segments_.size());
    static_assert(sizeof(float3) == 3 * sizeof(float));
    const auto put_float = [](std::string& out, float v) { put(out, v); };
    const auto put_float3 = [](std::string& out, const float3& v) { put(out, v.x), put(out, v.y), put(out, v.z); };
    column(at + 12 * first, block.positions(), put_float3);
    at += 12 * n;
    if (flags & kThickness) {
        column(at + 4 * first, width, put_float);
        at += 4 * n;
    }
    if (flags & kTransparency) {
        std::vector<float> transparency(opacity.size());
        for (size_t i = 0; i < opacity.size(); ++i) transparency[i] = 1.0f - opacity[i];
        column(at + 4 * first, std::span<const float>(transparency), put_float);
        at += 4 * n;
    }
    if (flags & kColor) column(at + 12 * first, color, put_float3);
    curves_ += block.num_curves();
    written_ += block.num_points();
}

void HairBlockWriter::start(uint32_t flags)
{
    started_ = true;
    flags_ = flags;
    std::string out;
    out += "HAIR";
    put<uint32_t>(out, static_cast<uint32_t>(segments_.size()));
    put<uint32_t>(out, static_cast<uint32_t>(points_));
    put<uint32_t>(out, flags);
    put<uint32_t>(out, 0);       // default segments: unused, every strand has its own count
    put<float>(out, 0.0f);       // default thickness: 0 = none given (read back without a width)
    put<float>(out, 0.0f);       // default transparency
    for (int k = 0; k < 3; ++k) put<float>(out, 1.0f);  // default colour
    std::string info = "groom " GROOM_VERSION;
    info.resize(88, '\0');
    out += info;
    put_at(0, out.data(), out.size());
    column(kHeader, std::span<const uint16_t>(segments_), [](std::string& o, uint16_t v) { put(o, v); });
}

void HairBlockWriter::finish()
{
    if (!started_) start(kSegments | kPoints);
    if (curves_ != segments_.size()) {
        throw InvalidParam("hair: " + std::to_string(curves_) + " of " + std::to_string(segments_.size()) + " announced strands were written");
    }
    stream_.seekp(0, std::ios::end);
}

void write_hair(const CurveSet& curves, std::ostream& stream)
{
    if (curves.num_curves() > UINT32_MAX || curves.num_points() > UINT32_MAX) throw InvalidParam("hair: more than 2^32 strands or points");
    std::vector<int64_t> counts(curves.num_curves());
    for (size_t c = 0; c < counts.size(); ++c) counts[c] = curves.points_in(c);
    // Written straight to the stream, each array at once: the whole file as one string first was a
    // copy of the output held beside the curves (issue 17: a million hairs' curl peaked at 1.8 GB
    // against 0.5 GB written).
    HairBlockWriter writer(stream, counts);
    writer.write(curves);
    writer.finish();
}

std::string write_hair(const CurveSet& curves)
{
    std::ostringstream s;
    write_hair(curves, s);
    return std::move(s).str();
}

}  // namespace groom::io
