#include "bench/support.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <thread>

#include <fmt/format.h>
#include <sys/utsname.h>

#include "bench/bench.hpp"
#include "gpu/vulkan_backend.hpp"
#include "cpu/cpu_backend.hpp"

namespace vkrt::bench {
namespace {

std::string read_first_value(const char* file, const std::string& key) {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind(key, 0) != 0) continue;
        const std::size_t colon = line.find(':');
        if (colon == std::string::npos) continue;
        const std::size_t start = line.find_first_not_of(" \t", colon + 1);
        return start == std::string::npos ? std::string() : line.substr(start);
    }
    return {};
}

}  // namespace

std::vector<std::unique_ptr<Backend>> make_backends(const BenchArgs& args) {
    std::vector<std::unique_ptr<Backend>> backends;
    if (args.backend != "cpu") backends.push_back(make_vulkan_backend(VulkanOptions{args.device, false}));
    if (args.backend != "vulkan") backends.push_back(make_cpu_backend());
    return backends;
}

void print_machine(const BenchArgs& args, const std::vector<std::unique_ptr<Backend>>& backends) {
    std::string cpu = read_first_value("/proc/cpuinfo", "model name");
    if (cpu.empty()) cpu = "unknown CPU";
    std::string memory;
    if (const std::string kib = read_first_value("/proc/meminfo", "MemTotal"); !kib.empty()) {
        memory = fmt::format(", {:.0f} GiB", std::stod(kib) / (1024.0 * 1024.0));
    }
    utsname os{};
    const std::string system = ::uname(&os) == 0 ? fmt::format(", {} {} {}", os.sysname, os.release, os.machine) : "";
    fmt::print("machine: {}, {} hardware threads{}{}\n", cpu, std::thread::hardware_concurrency(), memory, system);
    for (const auto& b : backends) {
        if (b->name() != "vulkan") continue;
        std::string driver;
        for (const DeviceInfo& d : list_vulkan_devices()) {
            if (d.name == b->device_name()) driver = fmt::format(" [{}], driver {}", d.type, d.driver);
        }
        fmt::print("vulkan:  {}{}\n", b->device_name(), driver);
    }
    fmt::print("command: {}\n", args.command_line);
}

std::string significant(double value, int digits) {
    if (value == 0.0 || !std::isfinite(value)) return fmt::format("{}", value);
    const int magnitude = int(std::floor(std::log10(std::fabs(value))));
    const int decimals = std::clamp(digits - 1 - magnitude, 0, 6);
    return fmt::format("{:.{}f}", value, decimals);
}

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace vkrt::bench
