#pragma once
// A subcommand of the vkrt program: its parsed options, and how to run it once the
// command line has been parsed. Each command's options are defined in its own
// *_command.cpp; the work is done by the module it names (render, bench, converge...).
#include <functional>
#include <vector>

#include <CLI/CLI.hpp>

namespace vkrt::cli {

struct Command {
    CLI::App* app = nullptr;    // the subcommand, owned by the program's CLI::App
    std::function<int()> run;   // its exit status; throws for errors reported as "error: ..."
    int error_status = 1;       // the exit status when run throws
};

Command add_render_command(CLI::App& program);
Command add_merge_command(CLI::App& program);
Command add_converge_command(CLI::App& program);
Command add_compare_command(CLI::App& program);
Command add_stack_command(CLI::App& program);
Command add_bench_command(CLI::App& program, int argc, char** argv);
Command add_devices_command(CLI::App& program);

// Parses the command line and runs the one command it names. Every mistake, in the
// command line or in the work, is one "error: " line on standard error.
int parse_and_run(CLI::App& program, const std::vector<Command>& commands, int argc, char** argv);

}  // namespace vkrt::cli
