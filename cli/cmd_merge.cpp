// `groom merge`: curve files one after another into one, every column carried: puts the parts of a
// `--shard I/N` run back together (cli/frame_options.h), byte for byte the whole run's output, in
// shard order and only when every shard is there once.
#include "cli/command.h"
#include "cli/frame_options.h"
#include "kernel/curve_set_edit.h"
#include "kernel/io/curve_io.h"

#include <algorithm>

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
    if (tagged == 0) return order;
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
        CurveSet all = std::move(parts[order[0]]);
        for (size_t k = 1; k < order.size(); ++k) all = join(all, parts[order[k]]);
        all.attributes(Domain::Detail).remove(kShardDetail);
        all.attributes(Domain::Detail).remove(kShardRunDetail);
        write_curves(all, args->output);
        note(common, "merge: " + std::to_string(all.num_curves()) + " curves, " + std::to_string(all.num_points()) + " points from " +
                         std::to_string(args->inputs.size()) + " files -> " + args->output);
    };
}

const Registrar reg({"merge", "Join curve files in order (the shards of a --shard run) into one", 950, setup});

}  // namespace
}  // namespace groom::cli
