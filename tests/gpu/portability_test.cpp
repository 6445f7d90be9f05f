// The instance and device set-up for portability implementations (gpu/portability.hpp):
// MoltenVK is listed only to an instance that enumerates portability drivers, and its
// devices need VK_KHR_portability_subset enabled. Tested on what a loader or device
// offers, since no such driver runs here.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "gpu/portability.hpp"

namespace {

using vkrt::gpu::device_extensions;
using vkrt::gpu::instance_setup;

std::vector<std::string> names(const std::vector<const char*>& list) { return {list.begin(), list.end()}; }

TEST(Portability, EnumerationFlagAndExtensionWhenTheLoaderOffersThem) {
    const auto setup = instance_setup({"VK_KHR_surface", "VK_KHR_portability_enumeration"}, false);
    EXPECT_EQ(names(setup.extensions), std::vector<std::string>{"VK_KHR_portability_enumeration"});
    EXPECT_EQ(setup.flags, VkInstanceCreateFlags(VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR));
}

TEST(Portability, NeitherWhereTheLoaderDoesNotOfferThem) {
    const auto setup = instance_setup({"VK_KHR_surface", "VK_EXT_debug_utils"}, false);
    EXPECT_TRUE(setup.extensions.empty());
    EXPECT_EQ(setup.flags, 0u);
}

TEST(Portability, ValidationAddsItsExtensionsBesidePortability) {
    const auto setup = instance_setup({"VK_KHR_portability_enumeration"}, true);
    EXPECT_EQ(names(setup.extensions), (std::vector<std::string>{"VK_EXT_debug_utils", "VK_EXT_validation_features",
                                                                 "VK_KHR_portability_enumeration"}));
    EXPECT_EQ(setup.flags, VkInstanceCreateFlags(VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR));
}

TEST(Portability, TheSubsetIsEnabledWhereverADeviceAdvertisesIt) {
    EXPECT_EQ(names(device_extensions({"VK_KHR_swapchain", "VK_KHR_portability_subset"})),
              std::vector<std::string>{"VK_KHR_portability_subset"});
    EXPECT_TRUE(device_extensions({"VK_KHR_swapchain"}).empty());
    EXPECT_TRUE(device_extensions({}).empty());
}

// This machine's loader lists its instance extensions (lavapipe's loader offers at
// least the surface extensions).
TEST(Portability, TheLoadersListReadsOnThisMachine) {
    const std::vector<std::string> offered = vkrt::gpu::offered_instance_extensions();
    EXPECT_FALSE(offered.empty());
}

}  // namespace
