#pragma once
// Drawing the convergence plot with gnuplot and scripts/plot_convergence.gp: vkrt
// writes the CSV, an existing plotting tool draws it.
#include <filesystem>
#include <string>
#include <vector>

namespace vkrt::converge {

// The gnuplot program: $VKRT_GNUPLOT when set (a path or a name on PATH), else
// gnuplot on PATH. Throws, naming the Debian package, when there is none.
std::string find_gnuplot();

// scripts/plot_convergence.gp of the source tree vkrt was built from; throws when
// it is not there.
std::filesystem::path plot_script();

// Runs gnuplot on the script: `curves` are the CSV's backend/estimator pairs to draw.
// Throws when gnuplot fails; its own messages go to standard error.
void plot_convergence(const std::string& gnuplot, const std::filesystem::path& script,
                      const std::filesystem::path& csv, const std::filesystem::path& png,
                      const std::vector<std::string>& curves);

}  // namespace vkrt::converge
