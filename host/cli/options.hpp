#pragma once
// The options several commands share, each defined once, and the validators that
// answer a wrong value with what was expected (CLI11's own Range answers "abc" with
// "not in range").
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "image/display.hpp"

namespace vkrt::cli {

// A whole number in [lo, hi].
CLI::Validator whole_number(std::uint64_t lo, std::uint64_t hi);
// A number >= 0.
CLI::Validator non_negative();
// A finite number of seconds above 0 (a budget of 0 could render nothing).
CLI::Validator positive_seconds();
// What `parse` accepts; a value it refuses with std::invalid_argument is answered
// with the exception's message. `name` is the value's form in --help (e.g. "A:B").
CLI::Validator accepted_by(std::function<void(const std::string&)> parse, const std::string& name);

// --width and --height, each overriding the scene's.
void add_image_size(CLI::App* command, std::optional<std::uint32_t>& width, std::optional<std::uint32_t>& height);
// --seed, overriding the scene's.
void add_seed(CLI::App* command, std::optional<std::uint32_t>& seed);
// --device: a Vulkan device by index or name.
void add_device(CLI::App* command, std::string& device);
// --threads: the reference backend's threads.
void add_threads(CLI::App* command, unsigned& threads);
// --validate: the Vulkan validation layer, any message an error.
void add_validate(CLI::App* command, bool& validate);
// --exposure and --tonemap: how 8-bit outputs show the linear image (image/display.hpp).
struct DisplayOptions {
    std::optional<double> exposure;
    std::string tonemap;  // empty: unchanged; else none or filmic
};
void add_display(CLI::App* command, DisplayOptions& display, const char* overrides);
// `base` with the options given applied.
Display display_with(Display base, const DisplayOptions& options);
// A colour given as one number for all three channels ("0.5") or three separated by
// commas ("1,0.9,0.8"), each finite and from 0 to 1e6; std::invalid_argument
// otherwise, saying what was expected.
std::array<double, 3> parse_colour(const std::string& text);
// -q, --quiet.
void add_quiet(CLI::App* command, bool& quiet, const char* description = "Print nothing but warnings and errors");

}  // namespace vkrt::cli
