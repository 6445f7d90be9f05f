#include "cli/options.hpp"

#include <cmath>
#include <functional>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

#include "scene/limits.hpp"

namespace vkrt::cli {
namespace {

// A validator for numbers read with `parse` (std::stoull, std::stod): the whole
// text must be the number and `accept` it, else the message says what was expected.
template <typename T>
CLI::Validator number(T (*parse)(const std::string&, std::size_t*), std::function<bool(T)> accept,
                      std::string expected, std::string name) {
    return CLI::Validator(
        [parse, accept, expected](std::string& text) -> std::string {
            std::size_t used = 0;
            T value{};
            try {
                value = parse(text, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            // stoull reads "-1" as a huge number; no whole number here has a sign.
            const bool sign_refused = std::is_unsigned_v<T> && !text.empty() && text[0] == '-';
            if (used == 0 || used != text.size() || sign_refused || !accept(value)) {
                return fmt::format("expected {}, got '{}'", expected, text);
            }
            return {};
        },
        std::move(name));
}

unsigned long long parse_whole(const std::string& text, std::size_t* used) { return std::stoull(text, used); }
double parse_real(const std::string& text, std::size_t* used) { return std::stod(text, used); }

}  // namespace

CLI::Validator accepted_by(std::function<void(const std::string&)> parse, const std::string& name) {
    return CLI::Validator(
        [parse = std::move(parse)](const std::string& text) {
            try {
                parse(text);
            } catch (const std::invalid_argument& e) {
                return std::string(e.what());
            }
            return std::string();
        },
        name);
}

std::array<double, 3> parse_colour(const std::string& text) {
    std::vector<double> values;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        const std::string part = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        std::size_t used = 0;
        double v = 0.0;
        try {
            v = std::stod(part, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (part.empty() || used != part.size() || !(v >= 0.0 && v <= 1e6)) {
            throw std::invalid_argument(
                fmt::format("expected a number from 0 to 1e6, or three separated by commas (R,G,B), got '{}'", text));
        }
        values.push_back(v);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (values.size() == 1) return {values[0], values[0], values[0]};
    if (values.size() != 3) {
        throw std::invalid_argument(fmt::format("expected one number or three (R,G,B), got {} in '{}'", values.size(), text));
    }
    return {values[0], values[1], values[2]};
}

CLI::Validator whole_number(std::uint64_t lo, std::uint64_t hi) {
    return number<unsigned long long>(
        &parse_whole,
        [lo, hi](unsigned long long value) { return value >= lo && value <= hi; },
        fmt::format("a whole number from {} to {}", lo, hi), fmt::format("{}..{}", lo, hi));
}

CLI::Validator non_negative() {
    return number<double>(&parse_real, [](double value) { return value >= 0.0; }, "a number >= 0", ">= 0");
}

CLI::Validator positive_seconds() {
    return number<double>(&parse_real, [](double value) { return value > 0.0 && std::isfinite(value); },
                          "a number of seconds above 0", "SECONDS > 0");
}

void add_image_size(CLI::App* command, std::optional<std::uint32_t>& width, std::optional<std::uint32_t>& height) {
    command->add_option("--width", width, "Image width, overrides the scene")
        ->check(whole_number(1, limits::kMaxImageSide));
    command->add_option("--height", height, "Image height, overrides the scene")
        ->check(whole_number(1, limits::kMaxImageSide));
}

void add_display(CLI::App* command, DisplayOptions& display, const char* overrides) {
    const double most = limits::kMaxExposureStops;
    command
        ->add_option("--exposure", display.exposure,
                     fmt::format("8-bit outputs: scale the radiance by 2^STOPS before the tone map{}", overrides))
        ->check(number<double>(
            &parse_real, [most](double value) { return std::abs(value) <= most; },
            fmt::format("a number of stops from -{0} to {0}", most), "STOPS"));
    command
        ->add_option("--tonemap", display.tonemap,
                     fmt::format("8-bit outputs: none (clamp to 1) or filmic (ACES-like shoulder){}", overrides))
        ->check(CLI::IsMember({"none", "filmic"}));
}

Display display_with(Display base, const DisplayOptions& options) {
    if (options.exposure) base.exposure = *options.exposure;
    if (!options.tonemap.empty()) base.tonemap = parse_tonemap(options.tonemap).value();  // checked by the parser
    return base;
}

void add_seed(CLI::App* command, std::optional<std::uint32_t>& seed) {
    command->add_option("--seed", seed, "Random seed, overrides the scene")->check(whole_number(0, 0xffffffffu));
}

void add_device(CLI::App* command, std::string& device) {
    command->add_option("--device", device, "Vulkan device: index or name from `vkrt devices` (e.g. lavapipe)");
}

void add_threads(CLI::App* command, unsigned& threads) {
    command->add_option("--threads", threads, "CPU threads for the cpu backend (default: all)")
        ->check(whole_number(0, 1024));
}

void add_validate(CLI::App* command, bool& validate) {
    command->add_flag("--validate", validate,
                      "Enable the Vulkan validation layer; any message makes the command fail");
}

void add_quiet(CLI::App* command, bool& quiet, const char* description) {
    command->add_flag("-q,--quiet", quiet, description);
}

}  // namespace vkrt::cli
