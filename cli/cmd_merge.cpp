// `groom merge`: curve files one after another into one, every column carried: puts the parts of a
// `--shard I/N` run back together (cli/frame_options.h), byte for byte the whole run's output, in
// shard order and only when every shard is there once.
#include "cli/command.h"
#include "cli/frame_options.h"
#include "kernel/curve_set_edit.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/detail_text.h"

#include <algorithm>
#include <filesystem>

namespace groom::cli {
namespace {

struct Args {
    std::vector<std::string> inputs;
    std::string output;
};

/// The order to join `parts` in. Files with no shard tag (kShardDetail: another tool's, or .hair,
/// which cannot hold one) are joined as given. Shards of one `--shard I/N` run are joined by I
/// whatever order they were given in (a shell's glob puts 10 before 2), and must be all N, once
/// each: a part missing or given twice is refused, not merged into a groom with a hole or doubles.
std::vector<size_t> shard_order(const std::vector<std::string>& paths, const std::vector<CurveSet>& parts, const CommonOptions& common)
{
    std::vector<size_t> order(parts.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::vector<int64_t> index(parts.size(), -1);
    int64_t count = 0;
    size_t tagged = 0, first_tagged = 0;
    for (size_t k = 0; k < parts.size(); ++k) {
        const std::string tag = parts[k].detail_string(kShardDetail);
        if (tag.empty()) continue;
        int64_t i = -1, n = -1;
        const size_t slash = tag.find('/');
        try {
            if (slash != std::string::npos) i = std::stoll(tag.substr(0, slash)), n = std::stoll(tag.substr(slash + 1));
        }
        catch (const std::exception&) {
            i = n = -1;
        }
        if (!(n >= 1 && i >= 0 && i < n)) {
            throw InvalidGeometry(paths[k] + ": detail '" + kShardDetail + "' should be I/N with 0 <= I < N (written by --shard), found '" + tag + "'");
        }
        if (tagged == 0) first_tagged = k, count = n;
        if (n != count) {
            throw InvalidParam("merge: " + paths[first_tagged] + " is a shard of " + std::to_string(count) + " but " + paths[k] + " of " +
                               std::to_string(n) + ": give the shards of one --shard run");
        }
        index[k] = i;
        ++tagged;
    }
    if (tagged == 0) {
        // .hair cannot carry the tag: parts of a --shard run written as .hair are joined unchecked.
        size_t hair = 0;
        for (const std::string& p : paths) hair += std::filesystem::path(p).extension() == ".hair";
        if (hair > 1) {
            warn(common, "merge: warning: .hair files carry no shard tag, so a part missing, given twice or of another run cannot be told: joined in "
                         "the order given, unchecked (write --shard parts as .usda, .obj or .ply for a checked merge)");
        }
        return order;
    }
    // Parts of one run carry the same run key (parts written before it was kept carry none).
    const std::string first_run = parts[first_tagged].detail_string(kShardRunDetail);
    for (size_t k = 0; k < parts.size(); ++k) {
        const std::string run = parts[k].detail_string(kShardRunDetail);
        if (!run.empty() && !first_run.empty() && run != first_run) {
            throw InvalidParam("merge: " + paths[first_tagged] + " and " + paths[k] + " are shards of different runs (their commands differ in more " +
                               "than the shard and the output, or they are of different frames): give the shards of one --shard run");
        }
    }
    if (tagged != parts.size()) {
        const size_t plain = size_t(std::find(index.begin(), index.end(), -1) - index.begin());
        throw InvalidParam("merge: " + paths[first_tagged] + " is shard " + std::to_string(index[first_tagged]) + "/" + std::to_string(count) +
                           " of a --shard run but " + paths[plain] + " is not a shard: merge a run's shards on their own");
    }
    std::vector<int64_t> given(size_t(count), -1);
    for (size_t k = 0; k < parts.size(); ++k) {
        int64_t& at = given[size_t(index[k])];
        if (at >= 0) {
            throw InvalidParam("merge: shard " + std::to_string(index[k]) + "/" + std::to_string(count) + " is given twice (" + paths[size_t(at)] +
                               " and " + paths[k] + ")");
        }
        at = int64_t(k);
    }
    std::string missing;
    int64_t n_missing = 0;
    for (int64_t i = 0; i < count; ++i) {
        if (given[size_t(i)] >= 0) continue;
        if (++n_missing <= 8) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
    }
    if (n_missing > 0) {
        throw InvalidParam("merge: " + std::to_string(n_missing) + " of the " + std::to_string(count) + " shards of this --shard run are missing (" +
                           missing + (n_missing > 8 ? ", ..." : "") + "): a merge without them would leave their hair out");
    }
    bool moved = false;
    for (int64_t i = 0; i < count; ++i) {
        order[size_t(i)] = size_t(given[size_t(i)]);
        moved = moved || order[size_t(i)] != size_t(i);
    }
    if (moved) note(common, "merge: the " + std::to_string(count) + " shards joined in shard order, not the order given");
    return order;
}

/// A detail's value as a message shows it (the .obj/.ply comment text: "TYPE VALUE").
std::string detail_text(const Attribute& a)
{
    return io::plain_detail_name(a.name) ? io::detail_value_text(a, "merge") : std::string("(a value)");
}

/// Refuses parts that cannot be one groom, and says what a merge fills in. join() fills a column a
/// part lacks with -1 (ints) or 0 (floats), and keeps the first part's detail values: a trial's
/// merge of a .usda and an .obj part (OBJ keeps no widths) made a third of the hair width 0,
/// invisible, without a word, and a Y-up millimetre file joined a Z-up centimetre one as Z-up.
void check_parts_agree(const std::vector<std::string>& paths, const std::vector<CurveSet>& parts, const std::vector<size_t>& order,
                       bool shards, const CommonOptions& common)
{
    auto has_width = [](const CurveSet& cs) {
        return cs.attributes(Domain::Point).find(attr::width) || cs.attributes(Domain::Curve).find(attr::width);
    };
    // Columns: every name of any part, and the parts without it.
    std::string filled;
    for (Domain d : {Domain::Point, Domain::Curve}) {
        std::vector<std::string> names;
        for (const CurveSet& cs : parts)
            for (const Attribute& a : cs.attributes(d).all())
                if (std::find(names.begin(), names.end(), a.name) == names.end()) names.push_back(a.name);
        for (const std::string& name : names) {
            if (name == attr::width) continue;  // checked below, in either domain
            for (size_t k : order) {
                if (parts[k].attributes(d).find(name)) continue;
                if (shards) {
                    throw InvalidParam("merge: " + paths[k] + " has no " + domain_name(d) + " attribute '" + name +
                                       "', which other shards of its run have (its format cannot hold it?): write every shard in one format that keeps it, such as .usda");
                }
                filled += (filled.empty() ? "" : ", ") + ("'" + name + "' (" + domain_name(d) + ", not in " + paths[k] + ")");
                break;
            }
        }
    }
    size_t with = parts.size();
    for (size_t k : order)
        if (has_width(parts[k])) with = k;
    if (with != parts.size()) {
        for (size_t k : order) {
            if (has_width(parts[k])) {
                if (bool(parts[k].attributes(Domain::Point).find(attr::width)) != bool(parts[with].attributes(Domain::Point).find(attr::width))) {
                    throw InvalidParam("merge: " + paths[with] + " and " + paths[k] +
                                       " keep widths differently (one per point, one per curve): joined, each would get width 0 where it has none");
                }
                continue;
            }
            throw InvalidParam("merge: " + paths[k] + " has no widths but " + paths[with] +
                               " has: its hair would get width 0, invisible (.obj and .hair keep none; .usda and .ply do): give it widths "
                               "(every op that makes hair takes --root-width) or merge it on its own");
        }
    }
    if (!filled.empty()) warn(common, "merge: warning: columns not in every file are filled with -1 (integers) or 0 where missing: " + filled);
    // Details: the units and up axis must agree; others keep the first file's value, said when they differ.
    const size_t first = order[0];
    for (size_t k : order) {
        if (k == first) continue;
        for (std::string_view name : {std::string_view("units"), std::string_view("up_axis")}) {
            // An up axis unsaid is Y (USD's default, which the .usda reader leaves unsaid, and OBJ's).
            const std::string none = name == "up_axis" ? "Y" : "";
            const std::string a = parts[first].detail_string(name, none), b = parts[k].detail_string(name, none);
            if (a != b && !a.empty() && !b.empty()) {
                throw InvalidParam("merge: " + paths[first] + " has " + std::string(name) + " '" + a + "' but " + paths[k] + " has '" + b +
                                   "': the curves would be joined in different " + (name == "units" ? "units" : "axes") + "; bring them to one first (`groom transform " +
                                   paths[k] + (name == "units" ? " --units " : " --up-axis ") + a + " -o FILE`)");
            }
            if (a != b) {
                warn(common, "merge: warning: " + (a.empty() ? paths[first] : paths[k]) + " does not say its " + std::string(name) + "; taken as " +
                                 (a.empty() ? paths[k] : paths[first]) + "'s ('" + (a.empty() ? b : a) + "')");
            }
        }
        for (const Attribute& col : parts[k].attributes(Domain::Detail).all()) {
            if (col.name == "units" || col.name == "up_axis" || col.name == attr::closed || col.name == kShardDetail || col.name == kShardRunDetail) continue;
            const Attribute* mine = parts[first].attributes(Domain::Detail).find(col.name);
            if (mine && mine->data != col.data) {
                warn(common, "merge: warning: detail '" + col.name + "' is '" + detail_text(*mine) + "' in " + paths[first] + " but '" +
                                 detail_text(col) + "' in " + paths[k] + "; the output keeps the first");
            }
        }
    }
}

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("CURVES", args->inputs, "Curve files (" + curve_formats() + "), in order; the shards of a --shard run in any order (all of them, once each)")->required();
    app->add_option("-o,--output", args->output, "Output curves")->required();
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        for (const std::string& in : args->inputs) check_output(args->output, {in}, common);
        std::vector<CurveSet> parts;
        for (const std::string& in : args->inputs) parts.push_back(read_curves(in));
        const std::vector<size_t> order = shard_order(args->inputs, parts, common);
        check_parts_agree(args->inputs, parts, order, !parts[order[0]].detail_string(kShardDetail).empty(), common);
        CurveSet all = std::move(parts[order[0]]);
        for (size_t k = 1; k < order.size(); ++k) all = join(all, parts[order[k]]);
        all.attributes(Domain::Detail).remove(kShardDetail);
        all.attributes(Domain::Detail).remove(kShardRunDetail);
        write_curves(all, args->output);
        warn_up_axis_unsaid("merge", all, args->output, common);
        note(common, "merge: " + std::to_string(all.num_curves()) + " curves, " + std::to_string(all.num_points()) + " points from " +
                         std::to_string(args->inputs.size()) + " files -> " + args->output);
    };
}

const Registrar reg({"merge", "Join curve files in order (the shards of a --shard run) into one", 950, setup});

}  // namespace
}  // namespace groom::cli
