// The one table of file formats: which extensions groom reads and writes, how a file is recognised
// by its first bytes, and which attributes each keeps. Every reader, writer, format check and help
// text goes through it, so a new format is its own file in kernel/io/ plus one row here.
//
// Formats groom cannot read have rows too (binary USD, Alembic): no OpenUSD or Alembic package
// exists in Debian, so such a file is refused by name with the command that converts it.
#pragma once

#include <iosfwd>

#include "kernel/curve_set.h"
#include "kernel/io/curve_io.h"
#include "kernel/polygon_soup.h"

#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace groom::io {

struct FileBytes;

/// What a row can do; a format may do several (.obj and .ply hold curves or meshes).
enum FormatCaps : unsigned {
    kReadCurves = 1u << 0,
    kWriteCurves = 1u << 1,
    kReadMesh = 1u << 2,
    kWriteMesh = 1u << 3,
};

struct Format {
    std::string_view extension;  ///< lower case, without the dot: "usda"
    std::string_view name;       ///< for messages: "USD ASCII BasisCurves"
    /// True when a file's first bytes say it is this format ("#usda", "ply", "HAIR"); null when the
    /// format has no signature. Used for stdin and for extensions shared by two encodings (.usd).
    bool (*sniff)(std::string_view head) = nullptr;
    CurveSet (*read_curves)(const FileBytes& file, const CurveReadOptions& options) = nullptr;
    /// The same read straight from a file on disk, for formats that can (the whole file is never
    /// in memory beside its curves); null = read_curves on the file's bytes.
    CurveSet (*read_curves_file)(const std::string& path, const CurveReadOptions& options) = nullptr;
    std::string (*write_curves)(const CurveSet& curves, const CurveWriteOptions& options) = nullptr;
    /// The same written straight to a stream, for formats that can (no second copy of a large output
    /// in memory); null = write_curves' string is written.
    void (*stream_curves)(const CurveSet& curves, const CurveWriteOptions& options, std::ostream& out) = nullptr;
    /// A writer taking the curves a block at a time into `out`, every curve's point count given
    /// first (an op's output never whole in memory); null = the format needs the whole set at once.
    std::unique_ptr<CurveBlockSink> (*open_blocks)(std::ostream& out, std::span<const int64_t> counts) = nullptr;
    PolygonSoup (*read_mesh)(const FileBytes& file) = nullptr;
    std::string (*write_mesh)(const PolygonSoup& soup) = nullptr;
    /// For a format that holds either (.obj, .ply): whether this file's content is curves.
    bool (*content_is_curves)(const FileBytes& file) = nullptr;
    /// Whether writing keeps a column (P is always kept); null = every column is kept.
    bool (*keeps)(Domain domain, const Attribute& column) = nullptr;
    /// Non-empty for a format groom refuses: why, and how to convert the file (reading) or what to
    /// write instead (writing).
    std::string_view refusal;
    std::string_view write_refusal;

    unsigned caps() const
    {
        return (read_curves ? kReadCurves : 0u) | (write_curves ? kWriteCurves : 0u) | (read_mesh ? kReadMesh : 0u) |
               (write_mesh ? kWriteMesh : 0u);
    }
    bool can(unsigned cap) const { return (caps() & cap) == cap; }
};

/// Every row, in the order help texts list them.
std::span<const Format> formats();

/// The row for an extension (lower case, no dot), or null when groom has never heard of it.
const Format* format_by_extension(std::string_view extension);

/// The row for a path's extension, or null.
const Format* format_of_path(const std::string& path);

/// The extensions of the rows that can do `cap`, each with its dot, joined by `separator`:
/// format_list(kReadCurves) == ".usda .obj .ply .hair".
std::string format_list(unsigned cap, std::string_view separator = " ");

/// The row that reads or writes `path` as `cap`, chosen by extension ("-" = stdin/stdout: by the
/// first bytes of `head` when reading, .usda when writing). `what` names the kind in messages
/// ("curve", "mesh"). Throws IoError (`error_is_param` false) or InvalidParam naming the path, the
/// extension found and the ones expected; a refused format's message says how to convert it.
const Format& format_for(const std::string& path, unsigned cap, std::string_view what, std::string_view head = {},
                         bool error_is_param = false);

}  // namespace groom::io
