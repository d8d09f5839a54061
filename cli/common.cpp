#include "cli/command.h"

#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/format_table.h"
#include "kernel/io/io_util.h"
#include "kernel/io/memory_files.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <mutex>

namespace groom::cli {

namespace {
thread_local std::vector<std::pair<std::string, std::string>> shown_paths;
}  // namespace

void set_shown_paths(std::vector<std::pair<std::string, std::string>> memory_to_user) { shown_paths = std::move(memory_to_user); }

std::string shown(const std::string& message)
{
    std::string out = message;
    for (const auto& [memory, user] : shown_paths) {
        for (size_t at = out.find(memory); at != std::string::npos; at = out.find(memory, at + user.size())) out.replace(at, memory.size(), user);
    }
    return out;
}

void note(const CommonOptions& o, const std::string& message)
{
    if (!o.quiet) std::cerr << shown(message) << "\n";
}

void detail(const CommonOptions& o, const std::string& message)
{
    if (o.verbose && !o.quiet) std::cerr << shown(message) << "\n";
}

void add_prim_option(CLI::App* app, CommonOptions& common)
{
    app->add_option("--prim", common.prims,
                    "USD input only: read this prim and the prims under it (an absolute path such as /groom/hair; repeatable)");
}

CurveSet read_curve_input(const std::string& path, const CommonOptions& common, bool main_input, int samples_per_segment)
{
    CurveReadOptions ro;
    ro.cubic_samples_per_segment = samples_per_segment;
    ro.warn = [&common, path](const std::string& w) { warn(common, "warning: " + w); };
    if (main_input && !common.prims.empty()) {
        const std::string ext = io::extension_of(path);
        if (path != "-" && ext != "usda" && ext != "usd") {
            throw InvalidParam("--prim picks prims of a USD file (.usda, .usd); " + path + " is a ." + ext + " file");
        }
        for (std::string p : common.prims) {
            while (p.size() > 1 && p.back() == '/') p.pop_back();
            if (p.empty() || p[0] != '/' || p.find("//") != std::string::npos) {
                throw InvalidParam("--prim " + p + ": expected an absolute prim path such as /groom/hair");
            }
            if (p != "/") ro.prims.push_back(p);
        }
    }
    return read_curves(path, ro);
}

std::string with_option_names(const std::string& message, const std::vector<std::string>& options)
{
    std::string out;
    size_t pos = 0;
    while (pos < message.size()) {
        const size_t open = message.find('`', pos);
        const size_t close = open == std::string::npos ? std::string::npos : message.find('`', open + 1);
        if (close == std::string::npos) break;
        std::string name = message.substr(open + 1, close - open - 1);
        const bool identifier = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
            return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
        });
        std::replace(name.begin(), name.end(), '_', '-');
        out.append(message, pos, open - pos);
        auto has = [&](const std::string& n) { return std::find(options.begin(), options.end(), n) != options.end(); };
        if (identifier && has(name)) {
            out += "--" + name;
        }
        else if (identifier && has("scalp-" + name)) {
            // A scalp build parameter (`voxel`, `band`, `flip`) is --scalp-voxel etc. on the commands
            // that convert a --scalp mesh on the fly (cli/scalp_options.h).
            out += "--scalp-" + name;
        }
        else {
            out.append(message, open, close + 1 - open);
        }
        pos = close + 1;
    }
    out.append(message, pos, std::string::npos);
    return out;
}

std::string curve_formats() { return io::format_list(io::kReadCurves); }
std::string mesh_formats() { return io::format_list(io::kReadMesh); }

namespace {

bool same_file(const std::string& a, const std::string& b)
{
    struct stat sa {}, sb {};
    if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return false;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

/// The file a path names, for comparing paths of files that may not exist yet: absolute, with every
/// link of its existing part resolved and `.`/`..` folded.
std::string resolved(const std::string& path)
{
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
    return ec ? path : p.string();
}

}  // namespace

bool names_one_file(const std::string& a, const std::string& b)
{
    return same_file(a, b) || resolved(a) == resolved(b);
}

namespace {

void check_one_output(const std::string& option, const std::string& output, std::span<const std::string> inputs, const CommonOptions& o)
{
    if (output.empty()) throw InvalidParam(option + ": an output path is required");
    if (output == "-" || is_memory_path(output)) return;  // (a --shard or --frames run's in-memory stage)
    // Refused before any work, and before any other output is written: a directory output was
    // found only at the rename, after a command's first output had already replaced the user's
    // file (a trial: `cornrow-guides -o cg.usda --tails-out DIR.usda`).
    struct stat st {};
    const bool exists = ::stat(output.c_str(), &st) == 0;
    if (exists && S_ISDIR(st.st_mode)) {
        throw InvalidParam(option + " " + output + " is a folder; expected a file to write (e.g. " +
                           (std::filesystem::path(output) / "out.usda").string() + ")");
    }
    const std::filesystem::path folder = std::filesystem::path(output).parent_path();
    std::error_code ec;
    if (!exists && !folder.empty() && output.find('#') == std::string::npos && !std::filesystem::is_directory(folder, ec)) {
        throw InvalidParam(option + " " + output + ": the folder " + folder.string() + " does not exist; create it first");
    }
    if (o.force) return;
    for (const std::string& in : inputs) {
        if (!in.empty() && in != "-" && same_file(in, output)) {
            throw InvalidParam(option + " " + output + " is also an input file; refusing to overwrite it (pass --force to allow)");
        }
    }
    // The rename that puts an output in place needs only the folder to be writable, so a file the
    // user made read-only would be replaced without a word: ask for --force, as `mv` asks. Read-only
    // by its mode as well as by access(): root may write any file, and render farms and containers
    // run as root (a `chmod 444` output was replaced there).
    const auto read_only = [&] { return (st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 || ::access(output.c_str(), W_OK) != 0; };
    if (exists && S_ISREG(st.st_mode) && read_only()) {
        throw InvalidParam(option + " " + output + " exists and is read-only; refusing to replace it (pass --force to replace it)");
    }
}

}  // namespace

void warn_up_axis_unsaid(const std::string& command, const CurveSet& curves, const std::string& output, const CommonOptions& o)
{
    if (curves.detail_string("up_axis") != "Z") return;
    const std::string ext = std::filesystem::path(output).extension().string();
    if (ext != ".obj" && ext != ".ply" && ext != ".hair") return;
    warn(o, command + ": warning: " + output + ": these curves are Z-up, and " + ext + " has no up axis: Blender's importer takes it as Y-up (turning it to Z-up), so "
                     "they will lie on their side there; write .usda (its upAxis says Z) or keep them Y-up for " + ext);
}

void check_output(const std::string& output, std::initializer_list<std::string> inputs, const CommonOptions& o)
{
    check_one_output("-o", output, std::span<const std::string>(inputs.begin(), inputs.size()), o);
}

void check_outputs(std::initializer_list<NamedOutput> outputs, std::initializer_list<std::string> inputs, const CommonOptions& o)
{
    check_outputs(outputs, std::span<const std::string>(inputs.begin(), inputs.size()), o);
}

void check_outputs(std::initializer_list<NamedOutput> outputs, std::span<const std::string> inputs, const CommonOptions& o)
{
    std::vector<const NamedOutput*> given;
    for (const NamedOutput& out : outputs) {
        if (out.path.empty()) continue;
        for (const NamedOutput* earlier : given) {
            if (names_one_file(earlier->path, out.path)) {
                throw InvalidParam(earlier->option + " " + earlier->path + " and " + out.option + " " + out.path +
                                   " name the same file; one output would replace the other: give them different names");
            }
        }
        check_one_output(out.option, out.path, inputs, o);
        given.push_back(&out);
    }
}

namespace {

/// Draws `label [#####.....] 42%` on a terminal, redrawn at most ~10 times per second.
class TerminalProgress final : public Progress {
public:
    explicit TerminalProgress(bool tty, bool verbose) : tty_(tty), verbose_(verbose) {}
    void begin(std::string_view label, int64_t total) override
    {
        std::lock_guard lock(mutex_);
        label_ = std::string(label);
        total_ = std::max<int64_t>(total, 1);
        done_ = 0;
        start_ = last_ = std::chrono::steady_clock::now();
        if (!tty_ && verbose_) std::cerr << label_ << " ...\n";
    }
    void advance(int64_t n) override
    {
        const int64_t done = done_ += n;
        if (!tty_) return;
        const auto now = std::chrono::steady_clock::now();
        std::unique_lock lock(mutex_, std::try_to_lock);
        if (!lock || now - last_ < std::chrono::milliseconds(100)) return;
        last_ = now;
        draw(done);
    }
    void end() override
    {
        std::lock_guard lock(mutex_);
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        if (tty_) {
            draw(total_);
            std::fprintf(stderr, " %.2fs\n", secs);
        }
        else if (verbose_) {
            std::fprintf(stderr, "%s done in %.2fs\n", label_.c_str(), secs);
        }
    }

private:
    void draw(int64_t done)
    {
        const double f = std::min(1.0, double(done) / double(total_));
        const int width = 30, filled = static_cast<int>(f * width);
        std::fprintf(stderr, "\r%-24s [%s%s] %3d%%", label_.c_str(), std::string(filled, '#').c_str(),
                     std::string(width - filled, '.').c_str(), static_cast<int>(f * 100.0));
        std::fflush(stderr);
    }

    bool tty_, verbose_;
    std::mutex mutex_;
    std::string label_;
    int64_t total_ = 1;
    std::atomic<int64_t> done_{0};
    std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace

std::unique_ptr<Progress> make_progress(const CommonOptions& o)
{
    if (o.quiet) return nullptr;
    const bool tty = ::isatty(STDERR_FILENO) != 0;
    if (!tty && !o.verbose) return nullptr;
    return std::make_unique<TerminalProgress>(tty, o.verbose);
}

float3 parse_float3(const std::string& option, const std::string& text)
{
    const std::vector<float> v = parse_floats(option, text, 3, 3);
    return {v[0], v[1], v[2]};
}

std::vector<float> parse_floats(const std::string& option, const std::string& text, size_t expected_min, size_t expected_max)
{
    std::vector<float> out;
    size_t start = 0;
    while (start <= text.size()) {
        size_t end = text.find(',', start);
        if (end == std::string::npos) end = text.size();
        std::string item = text.substr(start, end - start);
        // Trim spaces the shell may have let through.
        item.erase(0, item.find_first_not_of(' '));
        item.erase(item.find_last_not_of(' ') + 1);
        float v = 0.0f;
        const auto res = std::from_chars(item.data(), item.data() + item.size(), v);
        if (item.empty() || res.ec != std::errc() || res.ptr != item.data() + item.size() || !std::isfinite(v)) {
            throw InvalidParam(option + ": expected a comma-separated list of numbers, got '" + text + "' ('" + item +
                               "' is not a finite number)");
        }
        out.push_back(v);
        start = end + 1;
        if (end == text.size()) break;
    }
    if (out.size() < expected_min || out.size() > expected_max) {
        const std::string want = expected_min == expected_max ? std::to_string(expected_min)
                                                              : std::to_string(expected_min) + " to " + std::to_string(expected_max);
        throw InvalidParam(option + ": expected " + want + " comma-separated numbers, got " + std::to_string(out.size()) + " ('" +
                           text + "')");
    }
    return out;
}

FloatRange parse_range(const std::string& option, const std::string& text, FloatRange fallback)
{
    if (text.empty()) return fallback;
    const std::vector<float> v = parse_floats(option, text, 1, 2);
    return {v[0], v.size() > 1 ? v[1] : v[0]};
}

}  // namespace groom::cli
