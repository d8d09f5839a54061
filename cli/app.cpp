// The one place where errors become messages and exit codes.
#include "cli/command.h"

#include "kernel/error.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <iostream>
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

/// Where error() puts its message: stderr, or a caller's string (run_captured).
thread_local std::string* error_sink = nullptr;

void error(const std::string& message)
{
    if (error_sink) *error_sink = message;
    else std::cerr << "groom: error: " << message << "\n";
}

}  // namespace

Registrar::Registrar(CommandInfo info)
{
    registry().push_back(info);
}

int run(int argc, char** argv)
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
            ->check(CLI::NonNegativeNumber);
        sub->add_flag("-q,--quiet", common.quiet, "Print errors only");
        sub->add_flag("-v,--verbose", common.verbose, "Print more detail");
        sub->add_flag("--force", common.force, "Allow writing over an input file");
        contexts[i].app = sub;
        contexts[i].common = &common;
        commands[i].setup(contexts[i]);
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
                contexts[i].run();
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
            for (const std::string& extra : c.app->remaining()) {
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
    catch (const std::bad_alloc&) {
        error("out of memory");
        return 1;
    }
    catch (const std::exception& e) {
        error(std::string("unexpected failure: ") + e.what());
        return 1;
    }
}

int run_captured(const std::vector<std::string>& args, std::string& error_message)
{
    std::vector<std::string> words{"groom"};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    error_message.clear();
    error_sink = &error_message;
    struct Reset {
        ~Reset() { error_sink = nullptr; }
    } reset;
    return run(static_cast<int>(words.size()), argv.data());
}

}  // namespace groom::cli
