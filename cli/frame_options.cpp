#include "cli/frame_options.h"

#include "cli/command.h"
#include "cli/scalp_xform.h"
#include "fields/scalp_cache.h"
#include "kernel/curve_set_edit.h"
#include "kernel/error.h"
#include "kernel/io/atomic_file.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/io_util.h"
#include "kernel/io/memory_files.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

namespace groom::cli {

namespace {

/// The commands whose output is hair: they take --shard and --scalp-xform as well as --frames.
const std::set<std::string>& hair_commands()
{
    static const std::set<std::string> names{"generate", "curl", "braid", "puff", "gather", "edges", "populate", "cornrow-guides", "partition"};
    return names;
}

const char* const kFrames = "--frames";
const char* const kShard = "--shard";
const char* const kXform = "--scalp-xform";

struct FramePlan {
    std::string command;
    std::vector<std::string> words;  ///< args without the frame options (command first)
    std::optional<std::pair<long, long>> frames;
    int64_t shard = 0, shards = 1;
    std::string xform_path;
};

long parse_frame(const std::string& text, const std::string& spec)
{
    long v = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || v < 0 || v > 9999999) {
        throw InvalidParam(std::string(kFrames) + ": expected FIRST:LAST (or one frame), whole numbers from 0 to 9999999, got '" + spec + "'");
    }
    return v;
}

FramePlan parse_plan(const std::vector<std::string>& args)
{
    FramePlan plan;
    plan.command = args.empty() ? std::string() : args[0];
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        std::string name, value;
        for (const char* opt : {kFrames, kShard, kXform}) {
            const std::string o = opt;
            if (a == o) {
                if (i + 1 >= args.size()) throw InvalidParam(o + ": expected a value after it");
                name = o;
                value = args[++i];
            }
            else if (a.rfind(o + "=", 0) == 0) {
                name = o;
                value = a.substr(o.size() + 1);
            }
        }
        if (name.empty()) {
            plan.words.push_back(a);
            continue;
        }
        if (name != kFrames && !hair_commands().count(plan.command)) {
            throw InvalidParam(name + " is for the commands that make hair (generate, curl, braid, puff, gather, edges, populate, partition, "
                                      "cornrow-guides), not `" + plan.command + "`");
        }
        if (name == kFrames) {
            const size_t colon = value.find(':');
            const long first = parse_frame(value.substr(0, colon), value);
            const long last = colon == std::string::npos ? first : parse_frame(value.substr(colon + 1), value);
            if (last < first) throw InvalidParam(std::string(kFrames) + ": the last frame comes before the first ('" + value + "')");
            plan.frames = {first, last};
        }
        else if (name == kShard) {
            const size_t slash = value.find('/');
            auto num = [&](const std::string& t, int64_t& out) {
                const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
                return !t.empty() && r.ec == std::errc() && r.ptr == t.data() + t.size();
            };
            if (slash == std::string::npos || !num(value.substr(0, slash), plan.shard) || !num(value.substr(slash + 1), plan.shards) ||
                plan.shards < 1 || plan.shards > 1000000 || plan.shard < 0 || plan.shard >= plan.shards) {
                throw InvalidParam(std::string(kShard) + ": expected I/N with 0 <= I < N <= 1000000 (shard I of N, counted from 0), got '" + value + "'");
            }
        }
        else {
            plan.xform_path = value;
        }
    }
    if (!plan.xform_path.empty() && !plan.frames) {
        throw InvalidParam(std::string(kXform) + " " + plan.xform_path + ": give --frames FIRST:LAST too (the pose is read by frame)");
    }
    return plan;
}

/// `#` runs replaced by the frame number, zero-padded to the run's length.
std::string fill_pattern(const std::string& text, long frame)
{
    std::string out;
    for (size_t i = 0; i < text.size();) {
        if (text[i] != '#') {
            out += text[i++];
            continue;
        }
        size_t j = i;
        while (j < text.size() && text[j] == '#') ++j;
        std::string digits = std::to_string(frame);
        if (digits.size() < j - i) digits.insert(0, j - i - digits.size(), '0');
        out += digits;
        i = j;
    }
    return out;
}

/// Where an output path sits in the words: after -o/--output/--*-out, or after `=` in the long forms.
struct Slot {
    size_t index;       ///< word holding the path
    size_t offset;      ///< where the path starts in it
    std::string option;
};

bool output_option(const std::string& name)
{
    return name == "-o" || name == "--output" || (name.rfind("--", 0) == 0 && name.size() > 6 && name.compare(name.size() - 4, 4, "-out") == 0);
}

std::vector<Slot> output_slots(const std::vector<std::string>& words)
{
    std::vector<Slot> slots;
    for (size_t i = 1; i < words.size(); ++i) {
        const std::string& w = words[i];
        if (output_option(w) && i + 1 < words.size()) {
            slots.push_back({i + 1, 0, w});
            ++i;
        }
        else if (const size_t eq = w.find('='); eq != std::string::npos && output_option(w.substr(0, eq))) {
            slots.push_back({i, eq + 1, w.substr(0, eq)});
        }
    }
    return slots;
}

/// A curve file (not a mesh) that exists: what --scalp-xform brings into the rest frame.
bool existing_curve_file(const std::string& path)
{
    std::error_code ec;
    if (path.empty() || path[0] == '-' || !is_curve_path(path) || !std::filesystem::is_regular_file(path, ec)) return false;
    const std::string ext = io::extension_of(path);
    if (ext == "obj" || ext == "ply") return holds_curves(path);
    return true;
}

/// kShardRunDetail's value: FNV-1a over the words that make the output (see frame_options.h), each
/// ended by a zero byte, then the frame and the pose file.
std::string shard_run_key(const std::vector<std::string>& words, std::optional<long> frame, const std::string& xform_path)
{
    std::set<size_t> skip;
    for (const Slot& s : output_slots(words)) skip.insert(s.index);
    uint64_t h = 1469598103934665603ull;
    const auto add = [&h](const std::string& w) {
        for (const char c : w) h = (h ^ uint8_t(c)) * 1099511628211ull;
        h = (h ^ 0u) * 1099511628211ull;
    };
    for (size_t i = 0; i < words.size(); ++i) {
        const std::string& w = words[i];
        if (skip.count(i)) continue;
        if (w == "-q" || w == "--quiet" || w == "-v" || w == "--verbose" || w == "--force") continue;
        if (w == "--threads" || w == "--memory") {
            ++i;  // and its value
            continue;
        }
        if (w.rfind("--threads=", 0) == 0 || w.rfind("--memory=", 0) == 0) continue;
        add(w);
    }
    add(frame ? std::to_string(*frame) : std::string("-"));
    add(xform_path);
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    return hex;
}

/// One frame (or the one run of a shard without frames).
int run_frame(const FramePlan& plan, std::optional<long> frame, const RigidXform* pose,
              const std::function<int(std::vector<std::string>&)>& run_one)
{
    std::vector<std::string> words = plan.words;
    if (frame) {
        for (std::string& w : words) w = fill_pattern(w, *frame);
    }
    const bool reroute = pose || plan.shards > 1;
    struct Out {
        std::string option, path, memory;
    };
    std::vector<Out> outs;
    std::vector<std::string> memory_inputs;
    if (reroute) {
        const std::vector<Slot> slots = output_slots(words);
        std::set<size_t> out_words;
        for (const Slot& s : slots) {
            const std::string path = words[s.index].substr(s.offset);
            if (!is_curve_path(path) && path != "-") {
                throw InvalidParam(s.option + " " + path + ": --shard and --scalp-xform move and split curve outputs (" +
                                   curve_formats() + "); this one is not a curve file");
            }
            // The command checks its -o only as the memory path it is given: the real file is checked
            // here, as the command would (an input, or read-only, needs --force).
            CommonOptions checks;
            checks.force = std::find(words.begin(), words.end(), "--force") != words.end();
            check_outputs({{s.option, path}}, {}, checks);
            for (size_t i = 1; i < words.size(); ++i) {
                if (i != s.index) check_outputs({{s.option, path}}, {words[i]}, checks);
            }
            const std::string memory = "mem:" + path;
            outs.push_back({s.option, path, memory});
            words[s.index] = words[s.index].substr(0, s.offset) + memory;
            out_words.insert(s.index);
        }
        // Curve inputs named by a frame pattern are the frame's pose: into the rest frame.
        for (size_t i = 1; pose && i < words.size(); ++i) {
            if (out_words.count(i) || plan.words[i].find('#') == std::string::npos || !existing_curve_file(words[i])) continue;
            CurveSet in = read_curves(words[i]);
            transform_curves(in, *pose, true);
            const std::string memory = "mem:" + words[i] + "@rest";
            store_memory_curves(memory, std::move(in));
            memory_inputs.push_back(memory);
            words[i] = memory;
        }
    }
    const std::string run_key = plan.shards > 1 ? shard_run_key(words, frame, plan.xform_path) : std::string();
    std::vector<std::string> argv{"groom"};
    argv.insert(argv.end(), words.begin(), words.end());
    int rc = 0;
    ShardRequest& request = current_shard();
    request = ShardRequest{plan.shard, plan.shards, false};
    // The command's messages name the user's files, not the memory paths it was given.
    std::vector<std::pair<std::string, std::string>> aliases;
    for (const Out& o : outs) aliases.emplace_back(o.memory, o.path);
    for (const std::string& m : memory_inputs) aliases.emplace_back(m, m.substr(4, m.size() - 4 - 5));  // "mem:" PATH "@rest"
    set_shown_paths(aliases);  // an error's message is printed after a throw: run() clears them next time
    try {
        rc = run_one(argv);
        set_shown_paths({});
    }
    catch (...) {
        request = ShardRequest{};
        for (const std::string& m : memory_inputs) erase_memory_curves(m);
        for (const Out& o : outs) erase_memory_curves(o.memory);
        throw;
    }
    const bool claimed = request.claimed;
    request = ShardRequest{};
    for (const std::string& m : memory_inputs) erase_memory_curves(m);
    if (rc != 0) {
        for (const Out& o : outs) erase_memory_curves(o.memory);
        return rc;
    }
    OutputBatch batch;  // every output of the frame lands together, or none
    std::vector<CurveSet> results;
    for (const Out& o : outs) results.push_back(take_memory_curves(o.memory));
    for (size_t k = 0; k < outs.size(); ++k) {
        CurveSet& cs = results[k];
        if (plan.shards > 1 && !claimed) {
            // Shard I of N keeps the curves [I*C/N, (I+1)*C/N): `groom merge` of the shards in
            // order is the whole set, column by column, so a split run writes the same bytes.
            const int64_t c = static_cast<int64_t>(cs.num_curves());
            const int64_t begin = plan.shard * c / plan.shards, end = (plan.shard + 1) * c / plan.shards;
            std::vector<char> remove(cs.num_curves(), 1);
            std::fill(remove.begin() + begin, remove.begin() + end, 0);
            cs = remove_curves(cs, remove);
        }
        if (pose) transform_curves(cs, *pose, false);
        // Which part this is, for `groom merge` to put the parts in order and see one missing or
        // given twice (a shell's glob lists shard 10 before shard 2). Merge removes it again.
        if (plan.shards > 1) {
            cs.set_detail_string(kShardDetail, std::to_string(plan.shard) + "/" + std::to_string(plan.shards));
            cs.set_detail_string(kShardRunDetail, run_key);
        }
        write_curves(cs, outs[k].path, batch);
    }
    batch.commit();
    return 0;
}

}  // namespace

ShardRequest& current_shard()
{
    thread_local ShardRequest request;
    return request;
}

void add_frame_options(CLI::App* sub, const std::string& command)
{
    // Bound to values nobody reads: run_frames() takes these options out before CLI11 parses.
    static std::string unused;
    sub->add_option(kFrames, unused,
                    "FIRST:LAST: run once per frame; each `#` run in a file name becomes the frame number, zero-padded "
                    "(out.####.usda -> out.0007.usda)");
    if (!hair_commands().count(command)) return;
    sub->add_option(kShard, unused,
                    "I/N: write only part I of N of the output curves (counted from 0); `groom merge` of the N parts is the whole "
                    "output, byte for byte");
    sub->add_option(kXform, unused,
                    "FILE: the scalp's rigid pose per frame (lines `FRAME tx ty tz rx ry rz`, or a 3x4/4x4 matrix); the command runs "
                    "in the scalp's rest frame and its curves are moved to each frame's pose (needs --frames)");
}

bool wants_frames(const std::vector<std::string>& args)
{
    for (size_t i = 1; i < args.size(); ++i) {
        for (const std::string o : {kFrames, kShard, kXform}) {
            if (args[i] == o || args[i].rfind(o + "=", 0) == 0) return true;
        }
    }
    return false;
}

int run_frames(const std::vector<std::string>& args, const std::function<int(std::vector<std::string>&)>& run_one)
{
    const FramePlan plan = parse_plan(args);
    const bool quiet = std::any_of(plan.words.begin(), plan.words.end(), [](const std::string& w) { return w == "-q" || w == "--quiet"; });
    std::map<long, RigidXform> poses;
    if (!plan.xform_path.empty()) poses = read_scalp_xforms(plan.xform_path);
    if (plan.frames) {
        const auto [first, last] = *plan.frames;
        // Every frame's options are checked before the first runs: a farm should not find out at
        // frame 20 that a pose is missing.
        for (long f = first; !poses.empty() && f <= last; ++f) {
            if (!poses.count(f)) {
                throw InvalidParam(std::string(kXform) + " " + plan.xform_path + ": no pose for frame " + std::to_string(f) + " (frames " +
                                   std::to_string(poses.begin()->first) + " to " + std::to_string(poses.rbegin()->first) + " are given)");
            }
        }
        if (last > first) {
            for (const Slot& s : output_slots(plan.words)) {
                const std::string path = plan.words[s.index].substr(s.offset);
                if (path.find('#') == std::string::npos && path != "-") {
                    throw InvalidParam(s.option + " " + path + ": --frames " + std::to_string(first) + ":" + std::to_string(last) +
                                       " makes " + std::to_string(last - first + 1) +
                                       " frames, and every one would write over this file: name it with a frame pattern (out.####.usda)");
                }
            }
        }
        // And every frame's input files are there: a missing one was found at its frame, with the
        // frames before it written (a trial: guides.0003.usda missing, out.0001-0002 left behind).
        std::set<size_t> out_words;
        for (const Slot& s : output_slots(plan.words)) out_words.insert(s.index);
        for (size_t i = 1; i < plan.words.size(); ++i) {
            std::string pattern = plan.words[i];
            if (out_words.count(i) || pattern.find('#') == std::string::npos) continue;
            if (pattern[0] == '-') {
                const size_t eq = pattern.find('=');
                if (pattern.rfind("--", 0) != 0 || eq == std::string::npos) continue;
                pattern = pattern.substr(eq + 1);  // --option=FILE
            }
            std::string missing;
            long n_missing = 0;
            for (long f = first; f <= last; ++f) {
                const std::string path = fill_pattern(pattern, f);
                std::error_code ec;
                if (std::filesystem::exists(path, ec)) continue;
                if (++n_missing <= 5) missing += (missing.empty() ? "" : ", ") + path;
            }
            if (n_missing > 0) {
                throw IoError(pattern + ": " + std::to_string(n_missing) + " of the " + std::to_string(last - first + 1) + " frames' files are missing (" +
                              missing + (n_missing > 5 ? ", ..." : "") + "); no frame was run");
            }
        }
    }
    // A part written where its tag cannot go (.hair) cannot be checked by `groom merge`: a part
    // missing, given twice or out of order goes unnoticed (a trial). Said once, before any part.
    if (plan.shards > 1 && !quiet) {
        CurveSet probe;
        probe.set_detail_string(kShardDetail, "0/2");
        for (const Slot& s : output_slots(plan.words)) {
            const std::string path = plan.words[s.index].substr(s.offset);
            if (is_curve_path(path) && !attributes_dropped(probe, path).empty()) {
                std::cerr << "groom: warning: " << s.option << " " << path << ": this format cannot hold the part's --shard tag, so `groom merge` "
                          << "cannot put the parts in order or see one missing or given twice; write the parts as .usda, .ply or .obj\n";
            }
        }
    }
    // One field for every frame of a rigid head; a frame pattern of meshes rebuilds only on change.
    const ScalpCacheScope cache;
    if (!plan.frames) return run_frame(plan, std::nullopt, nullptr, run_one);
    const auto start = std::chrono::steady_clock::now();
    for (long f = plan.frames->first; f <= plan.frames->second; ++f) {
        const auto it = poses.find(f);
        const int rc = run_frame(plan, f, it == poses.end() ? nullptr : &it->second, run_one);
        if (rc != 0) return rc;
    }
    if (!quiet) {
        const long n = plan.frames->second - plan.frames->first + 1;
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char line[200];
        std::snprintf(line, sizeof line, "frames %ld-%ld: %ld frames in %.2f s (%.1f per minute)", plan.frames->first, plan.frames->second, n,
                      secs, secs > 0 ? 60.0 * double(n) / secs : 0.0);
        const long builds = ScalpCacheScope::builds();
        std::cerr << line << (builds == 0 ? "" : builds == 1 ? ", scalp field built once" : ", scalp field built " + std::to_string(builds) + " times")
                  << "\n";
    }
    return 0;
}

}  // namespace groom::cli
