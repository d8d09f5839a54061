// The one place where errors become messages and exit codes.
#include "cli/command.h"
#include "cli/frame_options.h"

#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/memory_budget.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <string_view>
#include <vector>

namespace groom::cli {

namespace {

std::vector<CommandInfo>& registry()
{
    static std::vector<CommandInfo> commands;
    return commands;
}

size_t edit_distance(std::string_view a, std::string_view b)
{
    std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        cur[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
        }
        std::swap(prev, cur);
    }
    return prev[b.size()];
}

/// The closest candidate within a small edit distance, or "".
std::string closest(std::string_view word, const std::vector<std::string>& candidates)
{
    std::string best;
    size_t best_d = std::max<size_t>(2, word.size() / 3) + 1;
    for (const std::string& c : candidates) {
        const size_t d = edit_distance(word, c);
        if (d < best_d || (d == best_d && best.empty() && c.rfind(word, 0) == 0)) {
            best_d = d;
            best = c;
        }
    }
    return best;
}

/// Where error() puts its message: stderr, or a caller's string (run_captured); where warn() puts
/// its warnings: note(), or a caller's list.
thread_local std::string* error_sink = nullptr;
thread_local std::vector<std::string>* warning_sink = nullptr;

/// The command being run and its long option names, for out_of_memory_message().
std::string g_command;
std::vector<std::string> g_options;
std::mutex g_running_mutex;

void error(const std::string& message)
{
    if (error_sink) *error_sink = shown(message);
    else std::cerr << "groom: error: " << shown(message) << "\n";
}

/// Integer options take decimal integers only. CLI11 reads them with strtoll(..., 0), so `--count 010`
/// was octal 8 and `0x10` 16, and a value past the type's range was clamped to its largest (ids then
/// wrapped); an unsigned option took -1 as 2^64 - 1. This check runs before CLI11's conversion:
/// leading zeros are dropped ("010" is ten), anything but an optional sign and digits is refused,
/// and so is a value outside int64 (uint64 for unsigned options, where a sign is refused).
void decimal_integers_only(CLI::Option* opt)
{
    const std::string type = opt->get_type_name();
    const bool is_unsigned = type.rfind("UINT", 0) == 0;
    if (!is_unsigned && type.rfind("INT", 0) != 0) return;
    opt->transform(CLI::Validator(
        [is_unsigned](std::string& text) -> std::string {
            std::string digits = text;
            const bool negative = !digits.empty() && digits[0] == '-';
            if (!digits.empty() && (digits[0] == '-' || digits[0] == '+')) digits.erase(0, 1);
            const bool decimal = !digits.empty() && digits.find_first_not_of("0123456789") == std::string::npos;
            if (!decimal || (is_unsigned && negative)) {
                return std::string("expected a decimal integer") + (is_unsigned ? " >= 0" : "") + ", got '" + text + "'";
            }
            digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size() - 1));
            text = (negative ? "-" : "") + digits;
            bool in_range = false;
            if (is_unsigned) {
                uint64_t v = 0;
                const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
                in_range = r.ec == std::errc() && r.ptr == text.data() + text.size();
            }
            else {
                int64_t v = 0;
                const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
                in_range = r.ec == std::errc() && r.ptr == text.data() + text.size();
            }
            if (!in_range) return "'" + text + "' is out of range for a 64-bit integer";
            return {};
        },
        ""));
}

/// The command's memory budget in bytes from --memory GiB, else GROOM_MEMORY (GiB), else 0 (the
/// default, half the machine's memory: kernel/memory_budget.h).
uint64_t memory_budget_from(const CommonOptions& common)
{
    auto bytes = [](double gib, const std::string& where) {
        if (!(std::isfinite(gib) && gib > 0.0 && gib <= 1.0e6)) {
            throw InvalidParam(where + " must be a memory budget in GiB, > 0 and at most 1e6 (got " + format_number(gib) + ")");
        }
        return static_cast<uint64_t>(std::max(gib * double(1ull << 30), 1.0));
    };
    if (common.memory_gib != 0.0) return bytes(common.memory_gib, "--memory");
    if (const char* env = std::getenv("GROOM_MEMORY"); env && *env) {
        const std::string text = env;
        double gib = 0.0;
        const auto r = std::from_chars(text.data(), text.data() + text.size(), gib);
        if (r.ec != std::errc() || r.ptr != text.data() + text.size()) {
            throw InvalidParam("GROOM_MEMORY must be a number of GiB (got '" + text + "')");
        }
        return bytes(gib, "GROOM_MEMORY");
    }
    return 0;
}

}  // namespace

void warn(const CommonOptions& o, const std::string& message)
{
    if (warning_sink) warning_sink->push_back(shown(message));
    else note(o, message);
}

std::string out_of_memory_message()
{
    std::string command;
    std::vector<std::string> options;
    {
        std::unique_lock lock(g_running_mutex, std::try_to_lock);
        if (lock) {
            command = g_command;
            options = g_options;
        }
    }
    const std::string note = memory_note();
    std::string msg = (command.empty() ? std::string() : command + ": ") + "out of memory";
    if (!note.empty()) msg += " (" + with_option_names(note, options) + ")";
    return msg + ": an allocation failed within the " + format_bytes(double(memory_budget())) +
           " memory budget (--memory, GROOM_MEMORY), so this machine has less free memory than that; ask for less, or lower "
           "--memory so that groom refuses too large a job before starting it";
}

Registrar::Registrar(CommandInfo info)
{
    registry().push_back(info);
}

namespace {

/// One pose: the command line as it was before --frames (cli/frame_options.h).
int run_one(int argc, char** argv)
{
    std::vector<CommandInfo> commands = registry();
    std::sort(commands.begin(), commands.end(), [](const CommandInfo& a, const CommandInfo& b) { return a.order < b.order; });

    CLI::App app{"groom: procedural hair grooming (braids, cornrows, edge hairs, curls, afro puffs) on real scalps.\n"
                 "Curves are .usda/.obj/.ply/.hair files; scalps are meshes or .vdb level sets from `groom scalp`.",
                 "groom"};
    app.set_version_flag("--version", std::string("groom ") + GROOM_VERSION);
    app.require_subcommand(1);
    app.footer("Run `groom COMMAND --help` for the options of one command.");

    CommonOptions common;
    std::vector<CommandContext> contexts(commands.size());
    std::vector<std::string> names;
    for (size_t i = 0; i < commands.size(); ++i) {
        CLI::App* sub = app.add_subcommand(commands[i].name, commands[i].summary);
        sub->add_option("--threads", common.threads, "Worker threads (0 = all cores); results are identical for any count")
            // CLI::NonNegativeNumber's message printed its range's top, DBL_MAX, in 309 digits.
            ->check(CLI::Validator(
                [](std::string& text) -> std::string {
                    return !text.empty() && text[0] == '-' ? "expected 0 (all cores) or a number of threads, got " + text : std::string();
                },
                ""));
        sub->add_flag("-q,--quiet", common.quiet, "Print errors only");
        sub->add_flag("-v,--verbose", common.verbose, "Print more detail");
        sub->add_flag("--force", common.force, "Allow writing over an input file or a read-only file");
        sub->add_option("--memory", common.memory_gib,
                        "Memory budget, GiB: larger outputs and scalp grids are refused before allocating (default: $GROOM_MEMORY, "
                        "else half this machine's memory, " + format_bytes(double(default_memory_budget())) + ")");
        contexts[i].app = sub;
        contexts[i].common = &common;
        commands[i].setup(contexts[i]);
        add_frame_options(sub, commands[i].name);
        for (CLI::Option* opt : sub->get_options()) decimal_integers_only(opt);
        names.emplace_back(commands[i].name);
    }

    // Unknown commands: CLI11 only says "not expected"; suggest the nearest command instead.
    if (argc >= 2 && argv[1][0] != '-' && std::find(names.begin(), names.end(), argv[1]) == names.end()) {
        std::string msg = std::string("unknown command '") + argv[1] + "'";
        if (std::string near = closest(argv[1], names); !near.empty()) msg += "; did you mean '" + near + "'?";
        error(msg + " (see `groom --help`)");
        return 2;
    }

    // The long option names of the command that ran (and the common ones), for error messages.
    auto parsed_options = [&] {
        std::vector<std::string> names;
        for (const CommandContext& c : contexts) {
            if (!c.app->parsed()) continue;
            for (const CLI::Option* o : c.app->get_options())
                for (const std::string& l : o->get_lnames()) names.push_back(l);
        }
        return names;
    };
    try {
        app.parse(argc, argv);
        for (size_t i = 0; i < commands.size(); ++i) {
            if (contexts[i].app->parsed() && contexts[i].run) {
                ThreadLimit limit(common.threads);
                MemoryLimit memory(memory_budget_from(common));
                {
                    const std::lock_guard lock(g_running_mutex);
                    g_command = commands[i].name;
                    g_options = parsed_options();
                }
                try {
                    const DroppedColumnsListener listen([&](const std::string& m) { note(common, std::string(commands[i].name) + ": " + m); });
                    contexts[i].run();
                }
                catch (const std::bad_alloc&) {
                    // Here, while the command's budget is still set, so the message states it.
                    throw LimitExceeded(out_of_memory_message());
                }
            }
        }
        return 0;
    }
    catch (const CLI::CallForHelp&) {
        std::cout << app.help();
        return 0;
    }
    catch (const CLI::CallForAllHelp&) {
        std::cout << app.help("", CLI::AppFormatMode::All);
        return 0;
    }
    catch (const CLI::Success& e) {
        return app.exit(e);  // --version
    }
    catch (const CLI::ExtrasError& e) {
        // Suggest the nearest option of the command that was being parsed.
        std::string msg = e.what();
        for (const CommandContext& c : contexts) {
            if (!c.app->parsed()) continue;
            std::vector<std::string> opts;
            for (const CLI::Option* o : c.app->get_options()) {
                for (const std::string& l : o->get_lnames()) opts.push_back("--" + l);
            }
            // Extra words that are not options: more inputs than the command takes (CLI11 lists
            // them last first), named in the order given; several curve files can be merged first.
            std::vector<std::string> words;
            const std::vector<std::string> extras = c.app->remaining();
            for (int k = 1; k < argc; ++k) {
                if (argv[k][0] != '-' && std::find(extras.begin(), extras.end(), argv[k]) != extras.end()) words.push_back(argv[k]);
            }
            if (!words.empty() && std::none_of(extras.begin(), extras.end(), [](const std::string& x) { return x.rfind("--", 0) == 0; })) {
                msg = c.app->get_name() + ": unexpected argument" + (words.size() > 1 ? "s" : "") + ":";
                for (const std::string& w : words) msg += " " + w;
                if (std::all_of(words.begin(), words.end(), [](const std::string& w) { return is_curve_path(w); })) {
                    msg += "; it takes one input file (to use several, merge them first: `groom merge A B ... -o all.usda`)";
                }
            }
            for (const std::string& extra : extras) {
                if (extra.rfind("--", 0) != 0) continue;
                const std::string key = extra.substr(0, extra.find('='));
                if (std::string near = closest(key, opts); !near.empty()) {
                    msg = c.app->get_name() + ": unknown option '" + key + "'; did you mean '" + near + "'?";
                }
                else {
                    msg = c.app->get_name() + ": unknown option '" + key + "'";
                }
                break;
            }
            msg += " (see `groom " + c.app->get_name() + " --help`)";
        }
        error(msg);
        return 2;
    }
    catch (const CLI::ParseError& e) {
        // Help requested on a subcommand is reported this way too.
        if (e.get_exit_code() == 0) return app.exit(e);
        std::string where;
        for (const CommandContext& c : contexts)
            if (c.app->parsed()) where = c.app->get_name() + ": ";
        error(where + e.what());
        return 2;
    }
    catch (const InvalidParam& e) {
        error(with_option_names(e.what(), parsed_options()));
        return 2;
    }
    catch (const Error& e) {
        error(with_option_names(e.what(), parsed_options()));
        return 1;
    }
    catch (const std::bad_alloc&) {  // outside a command's run (parsing)
        error(out_of_memory_message());
        return 1;
    }
    catch (const std::exception& e) {
        error(std::string("unexpected failure: ") + e.what());
        return 1;
    }
}

}  // namespace

int run(int argc, char** argv)
{
    const std::vector<std::string> args(argv + 1, argv + argc);
    set_shown_paths({});  // a frame's, left for its error by a run before (run_captured reuses the thread)
    if (!wants_frames(args)) return run_one(argc, argv);
    try {
        return run_frames(args, [](std::vector<std::string>& words) {
            std::vector<char*> frame_argv;
            for (std::string& w : words) frame_argv.push_back(w.data());
            frame_argv.push_back(nullptr);
            return run_one(static_cast<int>(words.size()), frame_argv.data());
        });
    }
    catch (const InvalidParam& e) {
        error(e.what());
        return 2;
    }
    catch (const Error& e) {
        error(e.what());
        return 1;
    }
    catch (const std::exception& e) {
        error(std::string("unexpected failure: ") + e.what());
        return 1;
    }
}

int run_captured(const std::vector<std::string>& args, std::string& error_message, std::vector<std::string>* warnings)
{
    std::vector<std::string> words{"groom"};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    error_message.clear();
    error_sink = &error_message;
    warning_sink = warnings;
    struct Reset {
        ~Reset() { error_sink = nullptr, warning_sink = nullptr; }
    } reset;
    return run(static_cast<int>(words.size()), argv.data());
}

}  // namespace groom::cli
