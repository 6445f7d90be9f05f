#pragma once
// `vkrt converge`: error against a reference over render time, per backend and
// estimator, as CSV and a log-log plot (docs/convergence.md). Returns the exit
// status; throws for errors the caller reports as "error: <message>".
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vkrt::converge {

struct ConvergeArgs {
    std::string scene;
    std::string reference;                 // empty: render one (reference_spp of path+nee)
    std::uint32_t reference_spp = 1024;
    std::vector<std::string> backends;     // empty: vulkan
    std::vector<std::string> estimators;   // empty: the scene's own settings
    std::optional<double> until;           // seconds of passes per curve
    std::optional<std::uint32_t> spp;      // samples per curve; with until, whichever ends first
    std::string csv;
    std::string plot;                      // empty: no plot
    std::optional<std::uint32_t> width;
    std::optional<std::uint32_t> height;
    std::optional<std::uint32_t> seed;
    std::string device;
    std::string serve;                     // "[ADDRESS:]PORT" of a live preview; empty: none
    unsigned threads = 0;
    bool validate = false;
    bool quiet = false;
};

// Without --spp or --until, a curve runs to this many samples per pixel.
inline constexpr std::uint32_t kDefaultConvergeSpp = 64;

int run_converge(const ConvergeArgs& args);

}  // namespace vkrt::converge
