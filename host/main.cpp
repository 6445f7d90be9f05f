// vkrt: the command line. Each command's options are in host/cli/*_command.cpp.
#include "cli/command.hpp"
#include "vkrt_version.h"

int main(int argc, char** argv) {
    using namespace vkrt::cli;
    CLI::App program{"vkrt: a ray tracer whose renderer is a Vulkan compute shader, with a C++ reference"};
    program.set_version_flag("--version", "vkrt " VKRT_VERSION " (kernel " VKRT_KERNEL_HASH ")");
    program.require_subcommand(1);
    const std::vector<Command> commands = {
        add_render_command(program),  add_merge_command(program),           add_converge_command(program),
        add_compare_command(program), add_stack_command(program),            add_bench_command(program, argc, argv),
        add_devices_command(program),
    };
    return parse_and_run(program, commands, argc, argv);
}
