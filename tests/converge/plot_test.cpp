// Drawing the convergence plot (host/converge/plot.cpp), with a stand-in for
// gnuplot that records how it was called: where the program is looked for
// ($VKRT_GNUPLOT, then PATH) and the message naming the package when it is not
// there, the script from the source tree, and the arguments gnuplot is given,
// quoted for it whatever the paths hold, without a shell in between.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "converge/plot.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt::converge;
namespace fs = std::filesystem;

// Sets an environment variable (or unsets it, given nothing) for the scope.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const std::optional<std::string>& value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        if (value) {
            setenv(name, value->c_str(), 1);
        } else {
            unsetenv(name);
        }
    }
    ~ScopedEnv() {
        if (old_) {
            setenv(name_, old_->c_str(), 1);
        } else {
            unsetenv(name_);
        }
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    const char* name_;
    std::optional<std::string> old_;
};

// An executable `name` in `dir` that writes its arguments, one a line, to
// dir/args.txt and exits with `status`.
fs::path stand_in(const fs::path& dir, const std::string& name, int status = 0) {
    const fs::path program = dir / name;
    std::ofstream(program) << "#!/bin/sh\nfor a in \"$@\"; do printf '%s\\n' \"$a\"; done > \"$(dirname \"$0\")/args.txt\"\n"
                           << "exit " << status << "\n";
    fs::permissions(program, fs::perms::owner_all);
    return program;
}

std::vector<std::string> lines_of(const fs::path& file) {
    std::ifstream in(file);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

std::string message_of(const std::function<void()>& call) {
    try {
        call();
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no error";
    return {};
}

TEST(FindGnuplot, TheVariableFirstThenPath) {
    const fs::path dir = vkrt::test::temp_dir("plot_find");
    const fs::path chosen = stand_in(dir, "myplot");
    fs::create_directories(dir / "bin");
    const fs::path on_path = stand_in(dir / "bin", "gnuplot");
    const ScopedEnv path("PATH", "/nonexistent:" + (dir / "bin").string());
    {
        const ScopedEnv variable("VKRT_GNUPLOT", chosen.string());
        EXPECT_EQ(find_gnuplot(), chosen.string());
    }
    {
        // A bare name is looked for along PATH, as the shell would.
        const ScopedEnv variable("VKRT_GNUPLOT", "gnuplot");
        EXPECT_EQ(find_gnuplot(), on_path.string());
    }
    {
        const ScopedEnv variable("VKRT_GNUPLOT", std::nullopt);
        EXPECT_EQ(find_gnuplot(), on_path.string());
    }
    {
        const ScopedEnv variable("VKRT_GNUPLOT", "");
        EXPECT_EQ(find_gnuplot(), on_path.string()) << "an empty variable counts as unset";
    }
}

TEST(FindGnuplot, NamesThePackageWhenThereIsNone) {
    const fs::path dir = vkrt::test::temp_dir("plot_missing");
    // A file that is there but cannot be run is no program.
    std::ofstream(dir / "gnuplot") << "not a program\n";
    fs::permissions(dir / "gnuplot", fs::perms::owner_read | fs::perms::owner_write);
    const ScopedEnv path("PATH", dir.string());
    {
        const ScopedEnv variable("VKRT_GNUPLOT", std::nullopt);
        const std::string message = message_of([] { find_gnuplot(); });
        EXPECT_NE(message.find("--plot needs gnuplot"), std::string::npos) << message;
        EXPECT_NE(message.find("apt-get install gnuplot-nox"), std::string::npos) << message;
    }
    {
        const ScopedEnv variable("VKRT_GNUPLOT", "/nonexistent/gnuplot");
        const std::string message = message_of([] { find_gnuplot(); });
        EXPECT_NE(message.find("VKRT_GNUPLOT names '/nonexistent/gnuplot'"), std::string::npos) << message;
        EXPECT_NE(message.find("gnuplot-nox"), std::string::npos) << message;
    }
}

TEST(PlotScript, IsTheSourceTreesScript) {
    const fs::path script = plot_script();
    EXPECT_EQ(script, fs::path(VKRT_SOURCE_DIR) / "scripts" / "plot_convergence.gp");
    EXPECT_TRUE(fs::is_regular_file(script));
}

TEST(PlotConvergence, GivesGnuplotTheSettingsQuotedForIt) {
    const fs::path dir = vkrt::test::temp_dir("plot_args");
    const fs::path gnuplot = stand_in(dir, "gnuplot");
    // A quote and a space in a path: gnuplot's single quotes take a quote written twice.
    const fs::path csv = dir / "it's a.csv";
    plot_convergence(gnuplot.string(), "/src/plot.gp", csv, dir / "c.png", {"cpu/local", "vulkan/local"});
    EXPECT_EQ(lines_of(dir / "args.txt"),
              (std::vector<std::string>{"-e",
                                        "csv='" + (dir / "it''s a.csv").string() + "'; png='" +
                                            (dir / "c.png").string() + "'; curves='cpu/local vulkan/local'",
                                        "/src/plot.gp"}));
}

TEST(PlotConvergence, AFailingGnuplotIsAnError) {
    const fs::path dir = vkrt::test::temp_dir("plot_fails");
    const fs::path gnuplot = stand_in(dir, "gnuplot", 3);
    const std::string message = message_of(
        [&] { plot_convergence(gnuplot.string(), "/src/plot.gp", dir / "c.csv", dir / "c.png", {"cpu/local"}); });
    EXPECT_NE(message.find("failed drawing " + (dir / "c.png").string()), std::string::npos) << message;
    const std::string missing = message_of(
        [&] { plot_convergence((dir / "none").string(), "/src/plot.gp", dir / "c.csv", dir / "c.png", {}); });
    EXPECT_NE(missing.find("--plot: cannot run " + (dir / "none").string()), std::string::npos) << missing;
}

}  // namespace
