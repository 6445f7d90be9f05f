// The kernel's CHECK (host/kernel/checks.hpp): nothing while checks are off; while
// they are on, every violated invariant counted and the first one named.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "kernel/kernel.hpp"

namespace {

using vkrt::kernel::Kernel;
namespace checks = vkrt::kernel::checks;

// A diffuse material whose colour is NaN: its lobe weight and value are not weights.
Kernel::Lobes broken_lobes(Kernel& k) {
    vkrt::kernel::Material m{};
    m.diffuse = glm::vec3(std::numeric_limits<float>::quiet_NaN(), 0.5f, 0.5f);
    m.kd = 1.0f;
    return k.material_lobes(m, glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1));
}

class KernelChecks : public ::testing::Test {
protected:
    void SetUp() override {
        was_on_ = checks::enabled.load();
        checks::reset();
    }
    void TearDown() override {
        checks::enabled.store(was_on_);
        checks::reset();
    }
    bool was_on_ = false;
};

TEST_F(KernelChecks, OffTheyCostNothingAndCountNothing) {
    checks::enabled.store(false);
    Kernel k;
    const Kernel::Lobes l = broken_lobes(k);
    (void)k.eval_smooth(l, glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1));
    EXPECT_EQ(checks::failures.load(), 0u);
}

TEST_F(KernelChecks, OnEachViolationIsCountedAndTheFirstNamed) {
    checks::enabled.store(true);
    Kernel k;
    const Kernel::Lobes l = broken_lobes(k);  // the lobe weight check fails
    EXPECT_EQ(checks::failures.load(), 1u);
    EXPECT_NE(checks::first.find("is_finite_bits(l.diffuse.weight)"), std::string::npos) << checks::first;
    (void)k.eval_smooth(l, glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1));  // so does the value's
    EXPECT_EQ(checks::failures.load(), 2u);
}

TEST_F(KernelChecks, AValidMaterialPassesThem) {
    checks::enabled.store(true);
    Kernel k;
    vkrt::kernel::Material m{};
    m.diffuse = glm::vec3(0.5f);
    m.kd = 1.0f;
    const glm::vec3 n(0, 0, 1), wo = glm::normalize(glm::vec3(1, 0, 1)), wi = glm::normalize(glm::vec3(-1, 1, 2));
    const Kernel::Lobes l = k.material_lobes(m, n, n, wo);
    EXPECT_FLOAT_EQ(k.eval_smooth(l, n, wo, wi).x, 0.5f / vkrt::kernel::PI);
    EXPECT_EQ(checks::failures.load(), 0u) << checks::first;
}

}  // namespace
