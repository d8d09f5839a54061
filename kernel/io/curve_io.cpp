#include "kernel/io/curve_io.h"

#include "kernel/curve_set_edit.h"
#include "kernel/error.h"
#include "kernel/io/format_table.h"
#include "kernel/io/formats.h"
#include "kernel/io/io_util.h"
#include "kernel/io/memory_files.h"

#include <filesystem>

namespace groom {

bool is_curve_path(const std::string& path)
{
    if (is_memory_path(path)) return true;
    const io::Format* f = io::format_of_path(path);
    return f && f->can(io::kReadCurves);
}

namespace {

thread_local DroppedColumnsListener* g_dropped_listener = nullptr;  // the innermost, per thread


/// The `closed` mark kept only where every curve is a loop (its first point repeated at its end): a
/// file's mark cannot make an open curve a loop.
CurveSet& checked_loops(CurveSet& cs)
{
    if (is_closed(cs) && !all_loops(cs)) set_closed(cs, false);
    return cs;
}

}  // namespace

CurveSet read_curves(const std::string& path, const CurveReadOptions& options)
{
    if (is_memory_path(path)) return read_memory_curves(path);
    if (path != "-") {
        std::error_code dir_ec;
        if (std::filesystem::is_directory(path, dir_ec)) {  // it read "unknown curve format '.'"
            throw ParseError(path + ": is a directory, not a curve file (.usda .obj .ply .hair)");
        }
        const io::Format& fmt = io::format_for(path, io::kReadCurves, "curve");  // refuse by name before reading
        // A file that cannot be sized, or an empty one, takes the whole-file path for its message.
        std::error_code ec;
        const auto bytes = std::filesystem::file_size(path, ec);
        if (fmt.read_curves_file && !ec && bytes > 0) {
            CurveSet cs = fmt.read_curves_file(path, options);
            cs.validate(path);
            return checked_loops(cs);
        }
    }
    const io::FileBytes file = io::read_all(path);
    const io::Format& fmt = io::format_for(path, io::kReadCurves, "curve", file.data);
    if (file.data.empty()) throw ParseError(file.name + ": file is empty (expected " + std::string(fmt.extension) + " curves)");
    CurveSet cs = fmt.read_curves(file, options);
    cs.validate(file.name);
    return checked_loops(cs);
}

void write_curves(const CurveSet& curves, const std::string& path, const CurveWriteOptions& options)
{
    OutputBatch batch;
    write_curves(curves, path, batch, options);
    batch.commit();
}

void write_curves(const CurveSet& given, const std::string& path, OutputBatch& batch, const CurveWriteOptions& options)
{
    // Loops asked for closed are marked so, their first point repeated, whatever the format: .usda
    // and .obj say "closed" themselves (each point once), .ply keeps the mark and .hair the repeated
    // point. `groom hairline -o h.ply` had written an open curve (a review).
    const bool close = options.closed && !is_closed(given);
    const CurveSet looped = close ? with_closing_points(given) : CurveSet();
    const CurveSet& curves = close ? looped : given;
    if (is_memory_path(path)) {
        curves.validate("writing " + path);
        batch.defer([copy = curves, path]() mutable { store_memory_curves(path, std::move(copy)); });
        return;
    }
    const io::Format& fmt = io::format_for(path, io::kWriteCurves, "curve", {}, /*error_is_param=*/true);
    curves.validate("writing " + path);
    if (g_dropped_listener) DroppedColumnsListener::tell(DroppedColumnsListener::message(curves, path));
    if (fmt.stream_curves) {
        // Straight into the batch's temporary, which an error part-way removes (nothing lands).
        try {
            fmt.stream_curves(curves, options, batch.open(path));
        }
        catch (const InvalidParam& e) {
            throw InvalidParam("writing " + path + ": " + e.what());
        }
        return;
    }
    // Encode fully before opening the output, so an encoding error leaves no file behind; the error
    // names the file (an attribute USD cannot name said only "usda: ...": a trial).
    std::string bytes;
    try {
        bytes = fmt.write_curves(curves, options);
    }
    catch (const InvalidParam& e) {
        throw InvalidParam("writing " + path + ": " + e.what());
    }
    batch.open(path).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

DroppedColumnsListener::DroppedColumnsListener(std::function<void(const std::string&)> hear) : hear_(std::move(hear)), previous_(g_dropped_listener)
{
    g_dropped_listener = this;
}

DroppedColumnsListener::~DroppedColumnsListener() { g_dropped_listener = previous_; }

std::string DroppedColumnsListener::message(const CurveSet& curves, const std::string& path)
{
    if (path == "-") return {};
    const std::vector<std::string> lost = attributes_dropped(curves, path);
    if (lost.empty()) return {};
    std::string list;
    for (const std::string& a : lost) list += (list.empty() ? "" : ", ") + a;
    return path + ": " + std::filesystem::path(path).extension().string() + " cannot hold these attributes, dropped: " + list;
}

void DroppedColumnsListener::tell(const std::string& message)
{
    if (g_dropped_listener && !message.empty()) g_dropped_listener->hear_(message);
}

bool writes_curve_blocks(const std::string& path)
{
    if (is_memory_path(path)) return false;
    const io::Format* f = io::format_of_path(path);
    return f && f->open_blocks;
}

CurveBlockWriter::CurveBlockWriter(const std::string& path, OutputBatch& batch, std::span<const int64_t> counts) : path_(path)
{
    if (!writes_curve_blocks(path)) {
        std::string can;
        for (const io::Format& f : io::formats())
            if (f.open_blocks) can += (can.empty() ? "." : ", .") + std::string(f.extension);
        throw InvalidParam(path + ": only " + can + " is written a block of curves at a time");
    }
    sink_ = io::format_of_path(path)->open_blocks(batch.open(path), counts);
}

CurveBlockWriter::~CurveBlockWriter() = default;

void CurveBlockWriter::write(const CurveSet& block)
{
    block.validate("writing " + path_);
    if (!seen_) {
        // Told at finish(), on the caller's thread (blocks may be written on another).
        dropped_ = DroppedColumnsListener::message(block, path_);
        seen_ = true;
    }
    sink_->write(block);
}

void CurveBlockWriter::finish()
{
    sink_->finish();
    DroppedColumnsListener::tell(dropped_);
}

CurveBlockCounts write_curve_blocks(const std::string& path, const std::function<void(const CurveBlockStart&, const CurveBlockEmit&)>& run)
{
    OutputBatch batch;
    std::unique_ptr<CurveBlockWriter> writer;
    CurveBlockCounts n;
    run(
        [&](std::span<const int64_t> counts) {
            writer = std::make_unique<CurveBlockWriter>(path, batch, counts);
            n.curves = counts.size();
            for (const int64_t c : counts) n.points += size_t(c);
        },
        [&](const CurveSet& block) { writer->write(block); });
    if (!writer) throw InvalidParam(path + ": the op announced no curves to write");
    writer->finish();
    batch.commit();
    return n;
}

std::vector<std::string> attributes_dropped(const CurveSet& curves, const std::string& path)
{
    if (is_memory_path(path)) return {};
    const io::Format& fmt = io::format_for(path, io::kWriteCurves, "curve", {}, /*error_is_param=*/true);
    std::vector<std::string> lost;
    for (Domain d : {Domain::Point, Domain::Curve, Domain::Detail}) {
        for (const Attribute& a : curves.attributes(d).all()) {
            if (d == Domain::Point && a.name == attr::P) continue;
            if (fmt.keeps && !fmt.keeps(d, a)) {
                std::string what = std::string(domain_name(d)) + " " + a.name;
                if (a.type() == AttrType::Int64 && fmt.extension == "ply") {
                    what += " (64-bit values beyond 2^53, which PLY's 32-bit integers cannot hold and its doubles would round)";
                }
                lost.push_back(what);
            }
        }
    }
    return lost;
}

bool holds_curves(const std::string& path)
{
    if (path == "-" || is_memory_path(path)) return true;
    const io::Format* fmt = io::format_of_path(path);
    if (!fmt || !fmt->can(io::kReadCurves)) return false;
    if (!fmt->can(io::kReadMesh) || !fmt->content_is_curves) return true;
    return fmt->content_is_curves(io::read_all(path));
}

}  // namespace groom
