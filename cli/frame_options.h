// Animated grooms on the command line: --frames A:B, --shard i/n and --scalp-xform FILE, shared by
// every command. They are taken out of the argument list before CLI11 sees it and the command runs
// once per frame, with every `#` run in its arguments replaced by the frame number (`####` -> 0007),
// so each command stays a one-pose program and a farm can run any frame (or shard) on its own.
//
// Rest frame: with --scalp-xform, the scalp is used as it is (its rest pose, one field for all
// frames, never rebuilt), curve inputs named by a frame pattern are per-frame world space and are
// brought into the rest frame by the frame's inverse transform, inputs without a pattern are taken
// to be in the rest frame already, the command runs there, and its curve outputs are moved to the
// frame's pose. So a hair keeps its root on the scalp, its id and its randomness on every frame.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace groom::cli {

/// Adds --frames (every command) and --shard, --scalp-xform (commands that make hair) to a
/// subcommand's help. They are parsed by run_frames(), never by CLI11: the values bound here stay unused.
void add_frame_options(CLI::App* sub, const std::string& command);

/// Whether `args` (argv without the program name: command first) asks for frames, shards or a scalp
/// transform.
bool wants_frames(const std::vector<std::string>& args);

/// Runs `run_one` (the normal one-pose command line, program name included) once per frame, with
/// the frame options taken out, frame patterns filled and inputs/outputs moved as described above.
/// Stops at the first frame that fails and returns its exit code. Bad frame options are an
/// InvalidParam thrown before any frame runs.
int run_frames(const std::vector<std::string>& args, const std::function<int(std::vector<std::string>&)>& run_one);

/// The shard the running command is asked for (set by run_frames around each run of a command with
/// --shard). A command that can make only its part of the output (curves [I*C/N, (I+1)*C/N) of the
/// C its whole run would make, every column as the whole run has it) does so and sets `claimed`;
/// run_frames then writes its output as it is instead of cutting the whole output. Per thread: the
/// Python module may run commands on several threads.
struct ShardRequest {
    int64_t shard = 0, shards = 1;
    bool claimed = false;
};
ShardRequest& current_shard();

/// The detail string every output of a `--shard I/N` run carries: "I/N". `groom merge` reads it to
/// order the parts and refuses a set with one missing or repeated, then drops it, so the merged
/// file is the whole run's, byte for byte. Formats without detail values (.hair) lose it.
inline constexpr const char* kShardDetail = "shard";
/// Beside it, which run the part is of: 16 hex digits hashing the command's words (frame numbers
/// filled in) without its outputs and the options that change no output byte (--threads, --quiet,
/// --verbose, --force, --memory), with the frame and the pose file. `groom merge` refuses parts of
/// different runs (a trial merged a part of a 4,000-hair run, one of another seed and one of
/// another frame with a 5,000-hair run's, and got a groom of 4,666 hairs without a word).
inline constexpr const char* kShardRunDetail = "shard_run";

}  // namespace groom::cli
