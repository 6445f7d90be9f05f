// Vertex colours (kernel/vertex_data.glsl): a triangle's colours, interpolated by
// its barycentric weights, multiply its material's colour, and their alpha its
// opacity (kernel/alpha.glsl). In a white furnace (a uniform sky of radiance 1) a
// flat white Lambertian triangle returns its albedo exactly, so each pixel shows the
// vertex colour at its sample point.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <glm/glm.hpp>

#include "flatten/flat_scene.hpp"
#include "statistics.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

// A triangle around the origin, facing +z, its centroid at the origin, seen head-on
// from +z by one ray through each pixel's centre (15 x 15: the centre pixel's ray
// meets the centroid), under a uniform sky of radiance `sky`.
Scene coloured_triangle(const std::string& name, const std::string& material, const std::string& colors,
                        double sky) {
    Scene scene = test::scene_from_text(name, R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 40, "width": 15, "height": 15 },
      "render": { "mode": "global", "spp": 1, "jitter": false, "background": [)" +
                                                  std::to_string(sky) + ", " + std::to_string(sky) + ", " +
                                                  std::to_string(sky) + R"(] },
      "materials": { "m": )" + material + R"( },
      "objects": [ { "type": "triangle", "vertices": [[-1, -0.5773502691896258, 0], [1, -0.5773502691896258, 0],
                                                      [0, 1.1547005383792515, 0]],
                     "colors": )" + colors + R"(, "material": "m" } ]
    })");
    return scene;
}

const std::string kPrimaries = "[[1, 0, 0], [0, 1, 0], [0, 0, 1]]";

TEST(VertexColor, AWhiteTriangleInAFurnaceShowsItsInterpolatedColours) {
    const Scene scene = coloured_triangle("furnace", R"({ "diffuse": [1, 1, 1] })", kPrimaries, 1.0);
    ASSERT_TRUE(flatten_scene(scene).features.has(Feature::HAS_VERTEX_COLORS));
    const RenderOutcome out = test::render_cpu(scene);
    // The centroid: a third of each primary.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(out.image.pixel(7, 7)[c], 1.0f / 3.0f, 1e-5f) << c;
    // Every pixel on the triangle: weights that sum to 1; off it, the sky.
    std::size_t on = 0;
    for (std::uint32_t y = 0; y < 15; ++y) {
        for (std::uint32_t x = 0; x < 15; ++x) {
            const float* p = out.image.pixel(x, y);
            const bool sky = p[0] == 1.0f && p[1] == 1.0f && p[2] == 1.0f;
            if (sky) continue;
            ++on;
            EXPECT_NEAR(p[0] + p[1] + p[2], 1.0f, 1e-5f) << x << "," << y;
        }
    }
    EXPECT_GT(on, 40u);
    // Toward the red corner (bottom left of the image), red; toward the blue one (top), blue.
    EXPECT_GT(out.image.pixel(3, 10)[0], 0.6f);
    EXPECT_GT(out.image.pixel(7, 2)[2], 0.6f);
    const RenderOutcome vulkan = test::render_vulkan(scene);
    EXPECT_LE(test::max_abs_difference(out.image, vulkan.image), 1e-6f);
}

// They multiply the material's own colour, and a metallic-roughness base colour.
TEST(VertexColor, MultiplyTheMaterialsColour) {
    const Scene grey = coloured_triangle("grey", R"({ "diffuse": [0.5, 0.5, 0.5] })", kPrimaries, 1.0);
    const RenderOutcome out = test::render_cpu(grey);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(out.image.pixel(7, 7)[c], 0.5f / 3.0f, 1e-5f) << c;
    // A rough white dielectric in a furnace returns about 1 (decision 0040); tinted
    // red at every corner, its diffuse lobe returns red only.
    const Scene pbr = coloured_triangle("pbr", R"({ "base_color": [1, 1, 1], "roughness": 1 })",
                                        "[[1, 0, 0], [1, 0, 0], [1, 0, 0]]", 1.0);
    Scene many = pbr;
    many.render.spp = 256;
    const RenderOutcome tinted = test::render_cpu(many);
    EXPECT_GT(tinted.image.pixel(7, 7)[0], 0.9f);
    EXPECT_LT(tinted.image.pixel(7, 7)[1], 0.1f);  // the specular lobe's few percent
    const RenderOutcome vulkan = test::render_vulkan(many);
    EXPECT_LE(test::max_abs_difference(tinted.image, vulkan.image), 1e-5f);
}

// A vertex alpha below 1 makes a blend material's coverage vary: a triangle that
// emits 1, its vertices' alpha 0.3, over a sky of 0.2, converges to 0.44.
TEST(VertexColor, AlphaMultipliesTheOpacity) {
    Scene scene = coloured_triangle("alpha", R"({ "emission": [1, 1, 1], "alpha_mode": "blend" })", kPrimaries, 0.2);
    scene.render.spp = 256;
    ASSERT_FALSE(flatten_scene(scene).features.has(Feature::HAS_ALPHA)) << "alpha 1 everywhere: opaque";
    for (auto& c : *scene.triangles[0].colors) c = glm::vec4(1.0f, 1.0f, 1.0f, 0.3f);
    ASSERT_TRUE(flatten_scene(scene).features.has(Feature::HAS_ALPHA));
    const RenderOutcome out = test::render_cpu(scene);
    const float v = out.image.pixel(7, 7)[0];
    const test::ZTestResult z = test::z_test(v, 0.8 * std::sqrt(0.21 / 256.0), 0.44);
    EXPECT_GT(z.p_value, 1e-4) << z << ", pixel " << v;
    const RenderOutcome vulkan = test::render_vulkan(scene);
    EXPECT_LE(test::max_abs_difference(out.image, vulkan.image), 1e-6f);
}

}  // namespace
}  // namespace vkrt
