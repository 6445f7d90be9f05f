// The fuzzers' inputs replayed in the normal suite, through the entry point the
// harnesses use (tests/fuzz/loader_input.hpp; docs/fuzzing.md): every seed of
// tests/fuzz/corpus/ must load, and every file of tests/fuzz/regressions/ (inputs
// that once crashed or hung a loader, and hand-made hostile ones) must load or be
// refused with a one-line SceneError naming the file. A regression file with a
// sidecar <file>.expected must be refused with a message holding each of its lines.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz/loader_input.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
namespace test = vkrt::test;
using vkrt::fuzz::Loader;

struct Input {
    Loader loader;
    fs::path file;
    bool seed;  // from the corpus: a valid file
};

void PrintTo(const Input& input, std::ostream* os) { *os << input.file.string(); }

constexpr std::string_view kExpected = ".expected";

std::string read_bytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<Input> inputs() {
    std::vector<Input> out;
    for (Loader loader : {Loader::Json, Loader::Nff, Loader::Obj, Loader::Mtl, Loader::Gltf}) {
        for (const char* kind : {"corpus", "regressions"}) {
            const fs::path dir = test::source_dir() / "tests" / "fuzz" / kind / vkrt::fuzz::loader_name(loader);
            if (!fs::is_directory(dir)) continue;
            std::vector<fs::path> files;
            for (const auto& entry : fs::directory_iterator(dir)) {
                if (entry.is_regular_file() && !entry.path().string().ends_with(kExpected)) files.push_back(entry.path());
            }
            std::sort(files.begin(), files.end());
            for (const fs::path& file : files) out.push_back({loader, file, std::string_view(kind) == "corpus"});
        }
    }
    return out;
}

std::string test_name(const ::testing::TestParamInfo<Input>& info) {
    std::string name = std::string(info.param.seed ? "seed_" : "regression_") +
                       std::string(vkrt::fuzz::loader_name(info.param.loader)) + "_" + info.param.file.filename().string();
    for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    }
    return name;
}

// The lines of a sidecar, each a piece the message must hold.
std::vector<std::string> expected_pieces(const fs::path& sidecar) {
    std::vector<std::string> pieces;
    std::ifstream in(sidecar);
    for (std::string line; std::getline(in, line);) {
        if (!line.empty()) pieces.push_back(line);
    }
    return pieces;
}

class FuzzRegressionTest : public ::testing::TestWithParam<Input> {};

TEST_P(FuzzRegressionTest, LoadsOrIsRefusedWithItsError) {
    const Input& input = GetParam();
    const vkrt::fuzz::Scratch scratch(test::temp_dir("fuzz_regression"));
    // Anything but a SceneError escapes load() and fails the test.
    const std::optional<std::string> error = scratch.load(input.loader, read_bytes(input.file));
    if (input.seed) {
        EXPECT_FALSE(error) << "a seed of the corpus should load: " << *error;
        return;
    }
    const fs::path sidecar = input.file.string() + std::string(kExpected);
    if (!fs::exists(sidecar)) {
        // Loading is as good an answer as a refusal; a refusal must name the file.
        if (error) test::expect_error_message(*error, scratch.dir().string(), {});
        return;
    }
    ASSERT_TRUE(error) << "expected a refusal holding the lines of " << sidecar.string();
    std::vector<std::string> pieces = expected_pieces(sidecar);
    ASSERT_FALSE(pieces.empty()) << sidecar.string() << " is empty";
    for (const std::string& piece : pieces) {
        EXPECT_NE(error->find(piece), std::string::npos) << "missing '" << piece << "' in: " << *error;
    }
    test::expect_error_message(*error, scratch.dir().string(), {});
}

INSTANTIATE_TEST_SUITE_P(Inputs, FuzzRegressionTest, ::testing::ValuesIn(inputs()), test_name);

}  // namespace
