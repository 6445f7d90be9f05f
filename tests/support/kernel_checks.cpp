// Every test runs with the kernel's CHECKs on (host/kernel/checks.hpp), and a test
// program after whose tests the reference backend saw an invariant fail fails too,
// naming the first one (ctest runs one test a program). Linked into every test
// executable as an object, so that no test can leave it out.
#include <gtest/gtest.h>

#include "kernel/checks.hpp"

namespace {

class KernelCheckVerdict : public ::testing::Environment {
public:
    void SetUp() override { vkrt::kernel::checks::enabled.store(true); }
    void TearDown() override {
        const auto failures = vkrt::kernel::checks::failures.load();
        EXPECT_EQ(failures, 0u) << "the kernel's invariants failed " << failures << " times; the first: "
                                << vkrt::kernel::checks::first;
    }
};

[[maybe_unused]] const auto* const kVerdict = ::testing::AddGlobalTestEnvironment(new KernelCheckVerdict);

}  // namespace
