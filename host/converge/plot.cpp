#include "converge/plot.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "app/source_tree.hpp"

extern char** environ;

namespace vkrt::converge {
namespace {

constexpr const char* kPackage = "gnuplot-nox";

bool executable(const std::filesystem::path& file) {
    return std::filesystem::is_regular_file(file) && ::access(file.c_str(), X_OK) == 0;
}

// `name` as the shell would find it: a path as it is, a bare name along $PATH.
std::string on_path(const std::string& name) {
    if (name.find('/') != std::string::npos) return executable(name) ? name : std::string();
    const char* path = std::getenv("PATH");
    std::string_view dirs = path != nullptr ? path : "";
    while (!dirs.empty()) {
        const std::size_t colon = std::min(dirs.find(':'), dirs.size());
        const std::filesystem::path candidate = std::filesystem::path(dirs.substr(0, colon)) / name;
        if (!dirs.substr(0, colon).empty() && executable(candidate)) return candidate.string();
        dirs.remove_prefix(std::min(colon + 1, dirs.size()));
    }
    return {};
}

// A gnuplot string literal: in single quotes a quote is written twice.
std::string gnuplot_quote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
    return out + "'";
}

}  // namespace

std::string find_gnuplot() {
    if (const char* chosen = std::getenv("VKRT_GNUPLOT"); chosen != nullptr && *chosen != '\0') {
        const std::string found = on_path(chosen);
        if (found.empty()) {
            throw std::runtime_error(fmt::format(
                "--plot: VKRT_GNUPLOT names '{}', which is no program here (unset it to use gnuplot from PATH, "
                "installed by apt-get install {})",
                chosen, kPackage));
        }
        return found;
    }
    const std::string found = on_path("gnuplot");
    if (found.empty()) {
        throw std::runtime_error(fmt::format(
            "--plot needs gnuplot, which is not installed: apt-get install {} (./scripts/setup installs it), or "
            "leave out --plot",
            kPackage));
    }
    return found;
}

std::filesystem::path plot_script() {
    const std::filesystem::path script = app::source_tree_path("scripts/plot_convergence.gp");
    if (!std::filesystem::is_regular_file(script)) {
        throw std::runtime_error(fmt::format(
            "--plot: the plotting script {} is missing (it comes with vkrt's source tree)", script.string()));
    }
    return script;
}

void plot_convergence(const std::string& gnuplot, const std::filesystem::path& script,
                      const std::filesystem::path& csv, const std::filesystem::path& png,
                      const std::vector<std::string>& curves) {
    const std::string settings = fmt::format("csv={}; png={}; curves={}", gnuplot_quote(csv.string()),
                                             gnuplot_quote(png.string()), gnuplot_quote(fmt::format("{}", fmt::join(curves, " "))));
    // No shell in between: paths with spaces or quotes reach gnuplot as they are.
    std::vector<std::string> words{gnuplot, "-e", settings, script.string()};
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (const int error = ::posix_spawn(&pid, gnuplot.c_str(), nullptr, nullptr, argv.data(), environ); error != 0) {
        throw std::runtime_error(fmt::format("--plot: cannot run {}: {}", gnuplot, std::strerror(error)));
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) throw std::runtime_error(fmt::format("--plot: waiting for {} failed", gnuplot));
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        throw std::runtime_error(fmt::format("--plot: {} failed drawing {} from {} with {} (its messages are above)",
                                             gnuplot, png.string(), csv.string(), script.string()));
    }
}

}  // namespace vkrt::converge
