// The `groom` command framework: every subcommand lives in its own cli/cmd_NAME.cpp and registers
// itself with a static Registrar, so adding a command touches no shared file. cli/ is the only
// layer that parses arguments, prints, or decides exit codes.
#pragma once

#include "kernel/math/vec.h"
#include "kernel/progress.h"
#include "ops/float_range.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <initializer_list>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace groom {
class CurveSet;
}

namespace groom::cli {

/// Options every command takes.
struct CommonOptions {
    int threads = 0;       ///< 0 = all cores
    bool quiet = false;    ///< errors only
    bool verbose = false;  ///< extra detail on stderr
    bool force = false;    ///< allow -o onto an input file or a read-only file
    double memory_gib = 0; ///< --memory: the command's memory budget, GiB; 0 = GROOM_MEMORY, else half the machine's
    std::vector<std::string> prims; ///< --prim: USD prims to read from the main curve input (add_prim_option)
};

/// What a command's setup function gets: its CLI11 subcommand and the common options (already added).
/// The setup function adds its own options and sets `run`, called after parsing succeeds.
struct CommandContext {
    CLI::App* app = nullptr;
    CommonOptions* common = nullptr;
    std::function<void()> run;
};

struct CommandInfo {
    const char* name;
    const char* summary;
    int order;  ///< position in `groom --help`
    void (*setup)(CommandContext&);
};

/// Registers a command at static-initialisation time.
struct Registrar {
    explicit Registrar(CommandInfo info);
};

/// Runs the groom command line; returns the process exit code (0 ok, 2 usage error, 1 failure).
int run(int argc, char** argv);

/// The same for a program that embeds groom (the Python module): `args` without the program name;
/// the error message is returned in `error_message` instead of printed (empty on success). When
/// `warnings` is given, the command's warnings (warn()) are appended to it, --quiet or not, and
/// not printed: the embedding program shows them its own way (Python's warnings module).
int run_captured(const std::vector<std::string>& args, std::string& error_message, std::vector<std::string>* warnings = nullptr);

/// The message for an allocation that failed although the estimates fitted the budget: the command,
/// what was being allocated (kernel/memory_budget.h MemoryNote) with the option to change, and
/// --memory. For run()'s handler and for a terminate handler (cli/main.cpp), where OpenVDB's
/// bad_alloc-in-a-destructor ends up.
std::string out_of_memory_message();

// --- helpers for command implementations -----------------------------------------------------------

/// Paths a command is run with in place of the user's (`--shard` and `--scalp-xform` route outputs
/// and posed inputs through memory as "mem:PATH"), each with the user's own path, which every
/// message shows instead (note, detail, warn, error): a shard's note read "-> mem:out.usda".
/// Set for the current thread; an empty list clears it.
void set_shown_paths(std::vector<std::pair<std::string, std::string>> memory_to_user);
/// `message` with each such path replaced by the user's.
std::string shown(const std::string& message);

/// Messages on stderr: note() unless --quiet, detail() only with --verbose.
void note(const CommonOptions& o, const std::string& message);
void detail(const CommonOptions& o, const std::string& message);
/// A warning ("curl: warning: ..."): the result was made but may not be what the user meant. On
/// stderr unless --quiet; under run_captured with a warning list, handed to the caller instead
/// (the Python module ran every command --quiet, so its users never saw one: a trial on Ratboy,
/// a model in metres, got straight "curls" with no word why).
void warn(const CommonOptions& o, const std::string& message);

/// Warns when Z-up curves go to a format with no up axis (.obj, .ply, .hair): Blender's importers
/// take those as Y-up, and a trial's `transform --up-axis z` then `.obj` lay on its side there.
void warn_up_axis_unsaid(const std::string& command, const CurveSet& curves, const std::string& output, const CommonOptions& o);

/// Throws InvalidParam when `output` names the same file as one of `inputs` (by any spelling: a
/// link, `dir/./file`) or names an existing file this user may not write, and --force is absent
/// (so a typo cannot overwrite the user's input, nor a file protected on purpose), or when output
/// is empty.
void check_output(const std::string& output, std::initializer_list<std::string> inputs, const CommonOptions& o);

/// An output file and the option that names it ("-o", "--tails-out").
struct NamedOutput {
    std::string option, path;
};

/// check_output for every output of a command with several (empty paths are skipped: options not
/// given), and InvalidParam when two of them name one file, which --force does not allow: one
/// would silently replace the other.
void check_outputs(std::initializer_list<NamedOutput> outputs, std::initializer_list<std::string> inputs, const CommonOptions& o);
/// Whether two paths name one file: the same file where both exist, else the same place once
/// resolved (links, `.` and `..`).
bool names_one_file(const std::string& a, const std::string& b);
/// check_outputs for a command whose inputs are a list (`groom scalp HEAD EYES`).
void check_outputs(std::initializer_list<NamedOutput> outputs, std::span<const std::string> inputs, const CommonOptions& o);

/// A progress bar on stderr when it is a terminal, line-based when not (only with --verbose),
/// nothing with --quiet.
std::unique_ptr<Progress> make_progress(const CommonOptions& o);

/// The library names a parameter in its messages as `snake_case` (the op's params field, the Python
/// keyword); the command line shows it as the option a user typed: `knot_length` -> --knot-length,
/// for every name in `options` (long names without dashes). Other text is left as it is.
std::string with_option_names(const std::string& message, const std::vector<std::string>& options);

/// The extensions groom reads as curves (".usda .obj .ply .hair") and as meshes, for help texts:
/// taken from the format table (kernel/io/format_table.h), so a new format shows up everywhere.
std::string curve_formats();
std::string mesh_formats();

/// Adds `--prim PATH` (repeatable) to a command whose main input is curves: read only these USD prims
/// and their descendants.
void add_prim_option(CLI::App* app, CommonOptions& common);

/// Reads a curve input of a command: the reader's warnings (USD prims skipped...) go to stderr
/// through note(); --prim applies when `main_input` (a hairline or parting file is read whole).
/// `samples_per_segment`: points per cubic or NURBS segment.
CurveSet read_curve_input(const std::string& path, const CommonOptions& common, bool main_input = true, int samples_per_segment = 8);

/// Parses "x,y,z" (or "a,b" etc.) into floats, naming the option in errors.
std::vector<float> parse_floats(const std::string& option, const std::string& text, size_t expected_min, size_t expected_max);

/// Parses "lo,hi" or a single value (lo = hi) into a range, naming the option in errors; empty
/// text gives `fallback`.
FloatRange parse_range(const std::string& option, const std::string& text, FloatRange fallback);

/// Parses "x,y,z" (a point, a direction, a colour), naming the option in errors.
float3 parse_float3(const std::string& option, const std::string& text);

}  // namespace groom::cli
