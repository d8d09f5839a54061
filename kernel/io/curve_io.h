// Reading and writing curve files, chosen by extension:
//   .usda  USD BasisCurves and NurbsCurves (read: composed, transformed, cubic and NURBS curves evaluated
//          to polylines; write: linear BasisCurves); .usd when it is text
//   .obj   `l` polylines (+ `v`)
//   .ply   ASCII or binary; vertex element with any properties plus an `edge` element
//   .hair  Cem Yuksel's binary hair format
// "-" as a path means stdin/stdout in .usda. Writes are atomic (see atomic_file.h).
#pragma once

#include "kernel/curve_set.h"
#include "kernel/io/atomic_file.h"

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace groom {

namespace io {
/// What a format that can be written a block of curves at a time gives (its row's open_blocks;
/// .hair's HairBlockWriter): the blocks in order, then finish().
class CurveBlockSink {
public:
    virtual ~CurveBlockSink() = default;
    virtual void write(const CurveSet& block) = 0;
    virtual void finish() = 0;
};
}  // namespace io

/// Curve formats by extension, lower-case, without dot.
bool is_curve_path(const std::string& path);

struct CurveReadOptions {
    /// Points per segment when evaluating cubic USD curves (and each NURBS knot span) into polylines.
    int cubic_samples_per_segment = 8;
    /// USD only: read these prims and their descendants (absolute prim paths); empty = every prim.
    std::vector<std::string> prims;
    /// USD only: name each curve's prim: curve int attribute `prim` indexing the lines of detail
    /// string `prim_paths` (one prim path a line), for `groom select --prim`.
    bool prim_paths = false;
    /// Receives each warning (a prim skipped, a primvar left out, an arc to another file); null = dropped.
    std::function<void(const std::string&)> warn;
    /// OBJ and PLY edges: a closed loop of edges (what Blender exports for a closed curve) is read as
    /// one closed curve, its first point repeated at the end as a USD periodic curve reads; false: a
    /// ParseError. True everywhere: refused outside `--hairline`, a hairline exported from Blender
    /// could not even be read by `groom info` or `convert` (a trial); ops that need a root say so.
    bool closed_loops = true;
};

/// Reads a curve file. Throws ParseError (file, line or byte offset, expected vs found) or IoError.
/// The result is validated (CurveSet::validate).
CurveSet read_curves(const std::string& path, const CurveReadOptions& options = {});

enum class PlyEncoding { Binary, Ascii };

struct CurveWriteOptions {
    PlyEncoding ply_encoding = PlyEncoding::Binary;
    /// Every curve is closed, its last point joined to its first (a hairline): .usda writes
    /// `wrap = "periodic"`, .obj ends each `l` record with its first vertex again, so a DCC shows a
    /// closed loop; .ply and .hair write the points as they are. Read back, such a curve has its
    /// first point repeated at the end.
    bool closed = false;
};

/// Writes `curves` atomically to `path` (format by extension). Throws IoError / InvalidParam.
void write_curves(const CurveSet& curves, const std::string& path, const CurveWriteOptions& options = {});

/// The same into `batch`: encoded and written to its temporary now, renamed into place (or stored,
/// for a "mem:" path) with the command's other outputs by batch.commit().
void write_curves(const CurveSet& curves, const std::string& path, OutputBatch& batch, const CurveWriteOptions& options = {});

/// The columns of `curves` that the format of `path` cannot hold ("domain name" each, e.g.
/// "curve id"): .obj keeps only P; .hair keeps P and point width, opacity, Cd; .usda keeps
/// everything; .ply everything but int64 columns with values beyond +-2^53 (stored as double,
/// exact up to 2^53: such a column is left out, never rounded), named with that reason.
std::vector<std::string> attributes_dropped(const CurveSet& curves, const std::string& path);

/// Who hears which columns an output's format could not hold: while one is alive on a thread,
/// write_curves (and a CurveBlockWriter at finish) called there tell it "PATH: .ply cannot hold these
/// attributes, dropped: curve id (...)". The CLI listens while a command runs, the Python module
/// while groom.write runs; with none the loss goes unsaid (ops writing ids to .ply, beyond 2^53,
/// lost them without a word: a trial). Listeners nest; the innermost hears.
class DroppedColumnsListener {
public:
    explicit DroppedColumnsListener(std::function<void(const std::string&)> hear);
    ~DroppedColumnsListener();
    DroppedColumnsListener(const DroppedColumnsListener&) = delete;
    DroppedColumnsListener& operator=(const DroppedColumnsListener&) = delete;
    /// What writing `curves` to `path` drops, as the listener hears it; "" when nothing.
    static std::string message(const CurveSet& curves, const std::string& path);
    /// Tells the thread's listener `message` (unless it is empty or there is none).
    static void tell(const std::string& message);

private:
    std::function<void(const std::string&)> hear_;
    DroppedColumnsListener* previous_;
};

/// Whether the format of `path` can be written a block of curves at a time (CurveBlockWriter):
/// its row in the format table has open_blocks (.hair); the others are written from the whole set.
bool writes_curve_blocks(const std::string& path);

/// An output written a block of curves at a time, in order, for an op that never holds its whole
/// output (`groom curl` into .hair). Each block is validated as write_curves validates the whole.
class CurveBlockWriter {
public:
    /// Opens `path`'s temporary in `batch` (renamed into place by batch.commit()); `counts`: every
    /// output curve's point count. Throws InvalidParam where !writes_curve_blocks(path) or the
    /// format cannot hold these counts, before anything is written.
    CurveBlockWriter(const std::string& path, OutputBatch& batch, std::span<const int64_t> counts);
    ~CurveBlockWriter();
    /// The next curves of the output.
    void write(const CurveSet& block);
    /// Throws unless every announced curve was written.
    void finish();

private:
    std::string path_;
    std::unique_ptr<io::CurveBlockSink> sink_;
    bool seen_ = false;
    std::string dropped_;  ///< what the first block's columns lose, told at finish() on the caller's thread
};

/// What write_curve_blocks wrote.
struct CurveBlockCounts {
    size_t curves = 0, points = 0;
};

/// The start and emit callbacks of an op's block form (curl_blocks, generate_blocks).
using CurveBlockStart = std::function<void(std::span<const int64_t> counts)>;
using CurveBlockEmit = std::function<void(const CurveSet& block)>;

/// Writes an op's output into `path` as its blocks come: `run(start, emit)` calls the op's block form
/// with the two callbacks; the file lands (atomically) once the op returns, or not at all if it throws.
/// Needs writes_curve_blocks(path).
CurveBlockCounts write_curve_blocks(const std::string& path, const std::function<void(const CurveBlockStart&, const CurveBlockEmit&)>& run);

/// Whether a file that could be either (.obj, .ply) holds curves rather than a mesh, by content:
/// an OBJ with `l` records and no `f` is curves; a PLY with an `edge` or `curve` element and no
/// `face` is curves. .usda and .hair are always curves, .off and .stl always meshes.
/// Throws IoError when the file cannot be read.
bool holds_curves(const std::string& path);

}  // namespace groom
