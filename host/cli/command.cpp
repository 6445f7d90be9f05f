#include "cli/command.hpp"

#include <exception>
#include <string>

#include <fmt/format.h>

namespace vkrt::cli {

int parse_and_run(CLI::App& program, const std::vector<Command>& commands, int argc, char** argv) {
    try {
        program.parse(argc, argv);
    } catch (const CLI::Success& e) {  // --help, --version
        return program.exit(e);
    } catch (const CLI::ParseError& e) {
        // One line and status 1, like every other mistake (docs/cli.md).
        std::string names;
        for (const Command& c : commands) names += (names.empty() ? "" : ", ") + c.app->get_name();
        if (program.get_subcommands().empty() && argc > 1 && argv[1][0] != '-') {
            fmt::print(stderr, "error: unknown command '{}' (expected {})\n", argv[1], names);
            return 1;
        }
        std::string help = "vkrt --help";
        for (const Command& c : commands) {
            if (c.app->parsed()) help = "vkrt " + c.app->get_name() + " --help";
        }
        fmt::print(stderr, "error: {} (see {})\n", e.what(), help);
        return 1;
    }
    for (const Command& c : commands) {
        if (!c.app->parsed()) continue;
        try {
            return c.run();
        } catch (const std::exception& e) {
            fmt::print(stderr, "error: {}\n", e.what());
            return c.error_status;
        }
    }
    return 1;  // require_subcommand(1) makes this unreachable
}

}  // namespace vkrt::cli
