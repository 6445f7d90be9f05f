#pragma once
// What both of `vkrt bench`'s modes share: the backends to measure, the machine
// lines above a table, and the median the tables report.
#include <memory>
#include <string>
#include <vector>

#include "render/backend.hpp"

namespace vkrt::bench {

struct BenchArgs;

// The Vulkan backend unless --backend cpu, then the reference unless --backend vulkan.
std::vector<std::unique_ptr<Backend>> make_backends(const BenchArgs& args);

// What a pasted table needs to be read right: the CPU (both backends run on it
// here), the Vulkan device and driver, and the command, one line each.
void print_machine(const BenchArgs& args, const std::vector<std::unique_ptr<Backend>>& backends);

double median(std::vector<double> values);

// `digits` significant digits, at most 6 decimals: the figures span orders of
// magnitude (brute force over a million spheres to the grid over ten, a 9-primitive
// scene's preprocessing to a 50,000-primitive one's), so fixed decimals would
// print many of them as 0.00 or as noise.
std::string significant(double value, int digits = 3);

}  // namespace vkrt::bench
