// `vkrt devices`: its options; the work is run_devices (cli/commands.cpp).
#include <memory>

#include "cli/command.hpp"
#include "cli/commands.hpp"

namespace vkrt::cli {

Command add_devices_command(CLI::App& program) {
    auto args = std::make_shared<DevicesArgs>();
    CLI::App* d = program.add_subcommand("devices", "List the Vulkan devices");
    CLI::Option* float_profile =
        d->add_flag("--float-profile", args->float_profile,
                    "Probe each device's float arithmetic against the CPU's and print a table (docs/numerics.md)");
    d->add_option("--device", args->device, "With --float-profile: only this device, index or name (e.g. lavapipe)")
        ->needs(float_profile);
    d->add_option("--json", args->json, "With --float-profile: also write the profile to this JSON file")
        ->needs(float_profile);
    CLI::Option* limits = d->add_flag(
        "--limits", args->limits,
        "Print each device's limits that vkrt relies on, whether it can run vkrt, and its heuristics (docs/porting.md)");
    limits->excludes(float_profile);
    d->add_option("--profile", args->profile,
                  "With --limits: clamp the limits to a profile first (minimum, moltenvk-m1, turnip-adreno6xx)")
        ->needs(limits);
    return {d, [args] { return run_devices(*args); }};
}

}  // namespace vkrt::cli
