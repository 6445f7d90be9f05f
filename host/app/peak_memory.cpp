#include "app/peak_memory.hpp"

#include <fstream>
#include <string>

namespace vkrt::app {

std::uint64_t peak_resident_bytes() {
    // The child's own figure: a parent's wait4() ru_maxrss also counts the
    // parent's pages that the child shared until its exec.
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind("VmHWM:", 0) != 0) continue;
        try {
            return std::stoull(line.substr(6)) * 1024;  // "VmHWM:    123456 kB"
        } catch (const std::exception&) {
            return 0;
        }
    }
    return 0;
}

}  // namespace vkrt::app
