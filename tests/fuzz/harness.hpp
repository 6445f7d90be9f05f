#pragma once
// The body of every libFuzzer harness (tests/fuzz/*_fuzz.cpp): each input loaded
// through the shared entry point. The loader's SceneError is the expected answer
// to a bad input; anything else (another exception, a crash, a sanitizer report,
// a timeout) ends the run as a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>

#include "loader_input.hpp"

namespace vkrt::fuzz {

// The process's scratch directory, removed when the fuzzer exits normally; one
// left by a crash stays under $TMPDIR (scripts/fuzz points that into build-fuzz).
class HarnessScratch {
public:
    explicit HarnessScratch(Loader loader)
        : scratch_(std::filesystem::temp_directory_path() /
                   ("vkrt_fuzz_" + std::string(loader_name(loader)) + "_" + std::to_string(::getpid()))) {}
    ~HarnessScratch() {
        std::error_code ignored;
        std::filesystem::remove_all(scratch_.dir(), ignored);
    }
    HarnessScratch(const HarnessScratch&) = delete;
    HarnessScratch& operator=(const HarnessScratch&) = delete;

    const Scratch& scratch() const { return scratch_; }

private:
    Scratch scratch_;
};

inline int run_one(Loader loader, const std::uint8_t* data, std::size_t size) {
    static const HarnessScratch harness(loader);
    harness.scratch().load(loader, std::string_view(reinterpret_cast<const char*>(data), size));
    return 0;
}

}  // namespace vkrt::fuzz
