// The numerical-stability suite (docs/numerics.md), cases 1 to 3: scale. Shadow acne at scene scales 1, 1e3 and 1e5 (and a
// thin occluder that must still cast its shadow), a tiny far sphere and a huge near
// one against a double-precision mask, and a scene far from the origin rendering
// the same 8-bit image as at the origin; every case on both backends. The scenes are
// tests/scenes/stability/case{1,2,3}_*.json; their expectations are traced here in
// double, independently of the kernel.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include "image/image.hpp"
#include "render/render.hpp"
#include "scene/load_scene.hpp"
#include "flatten/flat_scene.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

using glm::dvec3;

constexpr double kInf = std::numeric_limits<double>::infinity();

Scene stability_scene(const std::string& name) {
    return load_scene(std::filesystem::path(VKRT_SOURCE_DIR) / "tests/scenes/stability" / name);
}

// ------------------------------------------------------------ the double tracer

struct Ray64 {
    dvec3 origin;
    dvec3 dir;  // unit
};

// The eye ray through continuous image position (x, y), from the camera alone: the
// same frame as the host builds (host/flatten/flat_scene.cpp), kept in double.
Ray64 eye_ray(const Camera& c, double x, double y) {
    const dvec3 forward = glm::normalize(c.look_at - c.eye);
    const dvec3 right = glm::normalize(glm::cross(forward, glm::normalize(c.up)));
    const dvec3 up = glm::cross(right, forward);
    const double pixel = 2.0 * std::tan(glm::radians(c.fov) / 2.0) / c.height;
    const dvec3 d = forward + right * (pixel * (x - c.width / 2.0)) - up * (pixel * (y - c.height / 2.0));
    return {c.eye, glm::normalize(d)};
}

// Nearest root beyond t_min, by the quadratic in the form that does not cancel:
// double has 29 bits more than float, ample for every scene here.
double hit_sphere(const Ray64& r, const Sphere& s, double t_min) {
    const dvec3 oc = r.origin - s.center;
    const double b = glm::dot(oc, r.dir);
    const dvec3 f = oc - b * r.dir;
    const double disc = s.radius * s.radius - glm::dot(f, f);
    if (disc < 0.0) return kInf;
    const double q = b >= 0.0 ? -(b + std::sqrt(disc)) : std::sqrt(disc) - b;
    const double c = glm::dot(oc, oc) - s.radius * s.radius;
    const double t0 = std::min(q, c / q), t1 = std::max(q, c / q);
    return t0 > t_min ? t0 : t1 > t_min ? t1 : kInf;
}

double hit_triangle(const Ray64& r, const Triangle& tri, double t_min) {
    const dvec3 e1 = tri.vertices[1] - tri.vertices[0], e2 = tri.vertices[2] - tri.vertices[0];
    const dvec3 n = glm::cross(e1, e2);
    const double denom = glm::dot(n, r.dir);
    if (denom == 0.0) return kInf;
    const double t = glm::dot(n, tri.vertices[0] - r.origin) / denom;
    if (!(t > t_min)) return kInf;
    const dvec3 p = r.origin + t * r.dir;
    // Inside when p lies on the inner side of every edge (three, or a parallelogram's four).
    std::vector<dvec3> corners(tri.vertices.begin(), tri.vertices.end());
    if (tri.parallelogram) corners.push_back(tri.vertices[0] + tri.vertices[2] - tri.vertices[1]);
    for (std::size_t k = 0; k < corners.size(); ++k) {
        const dvec3 a = corners[k], b = corners[(k + 1) % corners.size()];
        if (glm::dot(glm::cross(b - a, p - a), n) < 0.0) return kInf;
    }
    return t;
}

struct Hit64 {
    double t = kInf;
    int material = -1;  // -1: nothing
    dvec3 normal{0.0};  // unit, facing the ray
};

Hit64 closest(const Scene& s, const Ray64& r, double t_min) {
    Hit64 h;
    for (const Sphere& sp : s.spheres) {
        const double t = hit_sphere(r, sp, t_min);
        if (t < h.t) h = {t, int(sp.material), (r.origin + t * r.dir - sp.center) / sp.radius};
    }
    for (const Triangle& tri : s.triangles) {
        const double t = hit_triangle(r, tri, t_min);
        if (t < h.t) {
            h = {t, int(tri.material), glm::normalize(glm::cross(tri.vertices[1] - tri.vertices[0],
                                                                 tri.vertices[2] - tri.vertices[0]))};
        }
    }
    if (glm::dot(h.normal, r.dir) > 0.0) h.normal = -h.normal;
    return h;
}

// Where the kernel starts a shadow ray from p (ray.glsl, offset_ray_origin): each
// kernel coordinate (the scene's minus `origin`) moved along the normal by
// int(256 n) float ULPs of itself, or by 2^-16 n where it is under 1/32.
dvec3 kernel_offset(const dvec3& p, const dvec3& n, const dvec3& origin) {
    dvec3 q = p - origin;
    for (int i = 0; i < 3; ++i) {
        const double a = std::abs(double(float(q[i])));
        if (a < 1.0 / 32.0) {
            q[i] += 0x1p-16 * n[i];
        } else {
            int e = 0;
            std::frexp(a, &e);  // a = m 2^e, m in [0.5, 1): a float's ULP is 2^(e - 24)
            q[i] += double(int(256.0 * n[i])) * std::ldexp(1.0, e - 24);
        }
    }
    return origin + q;
}

// Which material's primitive blocks the segment from `from` to the light (the last
// found), or -1. `t_min` leaves out the point's own surface.
int blocker_of(const Scene& s, const dvec3& from, const dvec3& light, double t_min) {
    const double dist = glm::length(light - from);
    const Ray64 shadow{from, (light - from) / dist};
    int blocker = -1;
    for (const Sphere& sp : s.spheres) {
        if (hit_sphere(shadow, sp, t_min) < dist) blocker = int(sp.material);
    }
    for (const Triangle& tri : s.triangles) {
        if (hit_triangle(shadow, tri, t_min) < dist) blocker = int(tri.material);
    }
    return blocker;
}

// What a pixel's eye ray should see: which material, and whether the (one) light
// reaches the point, which primitive's material blocks it if not, and the light's
// part of the pixel's value in the material's colour channel.
struct Expected {
    int material = -1;
    bool lit = false;
    int blocker = -1;
    // The answer differs from the point the kernel offsets its shadow ray to: the
    // offset, 256 ULPs of the kernel's coordinates, moves a shadow's edge by itself
    // over the tangent of the light's elevation (1/1000 in case 1: half a pixel).
    bool moved_by_offset = false;
    double lit_part = 0.0;  // radiance the light adds where it reaches
    double base = 0.0;      // radiance without the light (ambient)

    bool operator==(const Expected& o) const {
        return material == o.material && lit == o.lit && blocker == o.blocker;
    }
};

int channel_of(const Material& m) {
    return m.diffuse.x >= m.diffuse.y && m.diffuse.x >= m.diffuse.z ? 0 : m.diffuse.y >= m.diffuse.z ? 1 : 2;
}

Expected expect_at(const Scene& s, const dvec3& origin, double x, double y) {
    const Ray64 r = eye_ray(s.camera, x, y);
    const Hit64 h = closest(s, r, 0.0);
    Expected e;
    e.material = h.material;
    if (h.material < 0) return e;
    const Light& light = s.lights.at(0);
    const dvec3 p = r.origin + h.t * r.dir;
    const dvec3 to_light = light.position - p;
    const double dist = glm::length(to_light);
    const dvec3 l = to_light / dist;
    const double cos_theta = glm::dot(h.normal, l);
    const Material& m = s.materials[h.material];
    const int c = channel_of(m);
    const double diffuse = m.kd * m.diffuse[c];
    const bool global = s.render.mode == RenderMode::Global;
    e.base = global ? 0.0 : s.render.ambient[c] * diffuse;
    e.lit_part = light.intensity * std::max(cos_theta, 0.0) *
                 (global ? diffuse / glm::pi<double>() / (dist * dist) : diffuse);
    if (!(cos_theta > 0.0)) return e;
    // Blocked by anything between (the point's own surface excluded by a start far
    // beyond double's error and far below any feature of the scenes).
    e.blocker = blocker_of(s, p, light.position, 1e-9 * dist);
    e.lit = e.blocker < 0;
    e.moved_by_offset = blocker_of(s, kernel_offset(p, h.normal, origin), light.position, 0.0) != e.blocker;
    return e;
}

// The expectation at a pixel's centre (aa 1 traces exactly there), and whether it
// holds 1/50 pixel around it too and from the offset shadow-ray origin: pixels where
// it does not sit on an edge (of an object, or of a shadow) are left out, where a
// float ray may rightly differ.
struct PixelExpectation {
    Expected at_centre;
    bool confident = true;
};

PixelExpectation expect_pixel(const Scene& s, const dvec3& origin, std::uint32_t px, std::uint32_t py) {
    const double x = px + 0.5, y = py + 0.5, d = 0.02;
    PixelExpectation out{expect_at(s, origin, x, y), true};
    for (auto [dx, dy] : {std::array{d, 0.0}, std::array{-d, 0.0}, std::array{0.0, d}, std::array{0.0, -d}}) {
        out.confident = out.confident && expect_at(s, origin, x + dx, y + dy) == out.at_centre;
    }
    out.confident = out.confident && !out.at_centre.moved_by_offset;
    return out;
}

// ------------------------------------------------------------ reading an image

float value(const Image& image, std::uint32_t px, std::uint32_t py, int c) {
    return image.rgb[3 * (std::size_t(py) * image.width + px) + c];
}

// The material a pixel shows: each scene here gives its materials different
// dominant colour channels over a black background.
int seen_material(const Scene& s, const Image& image, std::uint32_t px, std::uint32_t py) {
    int best = -1;
    float top = 1e-6f;
    for (std::size_t m = 0; m < s.materials.size(); ++m) {
        const float v = value(image, px, py, channel_of(s.materials[m]));
        if (v > top) {
            top = v;
            best = int(m);
        }
    }
    return best;
}

// Where the expectation is lit, whether the pixel is dark enough to be shadowed: below
// halfway between the unlit and the lit value.
bool looks_shadowed(const Scene& s, const Image& image, std::uint32_t px, std::uint32_t py, const Expected& e) {
    const int c = channel_of(s.materials[e.material]);
    return value(image, px, py, c) < e.base + 0.5 * e.lit_part;
}

struct ShadowCounts {
    std::size_t lit = 0;              // confident lit pixels of `surface`
    std::size_t falsely_shadowed = 0;
    std::size_t occluder_shadow = 0;  // confident pixels of `surface` shadowed by `occluder`
    std::size_t falsely_lit = 0;
    std::size_t label_mismatches = 0;  // confident pixels showing another material
    std::size_t unsure = 0;            // pixels left out: on an edge
    std::size_t moved = 0;             // of which the offset moves the shadow's edge past the centre
};

ShadowCounts count_shadows(const Scene& s, const Image& image, int surface, int occluder, bool labels) {
    ShadowCounts n;
    const dvec3 origin = flatten_scene(s).origin;
    for (std::uint32_t py = 0; py < s.camera.height; ++py) {
        for (std::uint32_t px = 0; px < s.camera.width; ++px) {
            const PixelExpectation pe = expect_pixel(s, origin, px, py);
            if (!pe.confident) {
                ++n.unsure;
                n.moved += pe.at_centre.moved_by_offset ? 1 : 0;
                continue;
            }
            const Expected& e = pe.at_centre;
            if (labels && seen_material(s, image, px, py) != e.material) ++n.label_mismatches;
            if (e.material != surface) continue;
            const bool dark = looks_shadowed(s, image, px, py, e);
            if (e.lit) {
                ++n.lit;
                n.falsely_shadowed += dark ? 1 : 0;
            } else if (e.blocker == occluder) {
                ++n.occluder_shadow;
                n.falsely_lit += dark ? 0 : 1;
            }
        }
    }
    return n;
}

int material_index(const Scene& s, const std::string& name) {
    for (std::size_t i = 0; i < s.materials.size(); ++i) {
        if (s.materials[i].name == name) return int(i);
    }
    ADD_FAILURE() << "no material " << name;
    return -1;
}

// ------------------------------------------------------ case 1: acne at scale

// Global mode on the same scene: direct light only (max_bounces 1: the light is
// gathered at the first hit, and the one bounce can meet no emitter), no jitter and
// one sample, so each pixel is deterministic; the light's intensity makes up for the 1/(pi r^2)
// that global mode applies, so the plane is about as bright as in local mode.
Scene as_global(Scene s) {
    s.render.mode = RenderMode::Global;
    s.render.max_bounces = 1;
    s.render.jitter = false;
    s.render.spp = 1;
    for (Light& l : s.lights) {
        const double r = glm::length(l.position - s.camera.look_at);
        l.intensity *= glm::pi<double>() * r * r;
    }
    return s;
}

class AcneAtScale : public ::testing::TestWithParam<std::string> {};

// A plane lit at a grazing angle (cos 1e-3: where acne shows first) with a ball
// resting on it and a sheet 1e-3 x scale above it whose shadow falls 1 x scale beside
// its footprint, at scale 1, 1e3 and 1e5. No lit plane pixel may be shadowed and
// every pixel of the sheet's shadow must be, in local and global mode, on both
// backends. Why the sheet's height: a shadow ray leaves the plane 256 ULPs of its
// coordinates above it (ray.glsl), at most 2^-15 of the scene's largest kernel
// coordinate, about 3 x scale here, i.e. 1e-4 x scale; 1e-3 x scale is ten times that
// and some 8,000 float ULPs of those coordinates, so the sheet is thin where float
// resolution is concerned and yet must not be skipped by the offset.
TEST_P(AcneAtScale, NoFalseShadowsAndTheThinSheetStillCastsOne) {
    const Scene local = stability_scene(GetParam());
    const int plane = material_index(local, "plane");
    const int sheet = material_index(local, "sheet");
    for (const Scene& s : {local, as_global(local)}) {
        const bool global = s.render.mode == RenderMode::Global;
        for (bool vulkan : {false, true}) {
            SCOPED_TRACE(fmt::format("{}, {} mode, {}", GetParam(), global ? "global" : "local",
                                     vulkan ? "vulkan" : "cpu"));
            const RenderOutcome out = vulkan ? test::render_vulkan(s) : test::render_cpu(s);
            test::expect_sane(out);
            // Shadowed pixels are black in global mode, so only local mode's ambient
            // shows which material a shadowed pixel is.
            const ShadowCounts n = count_shadows(s, out.image, plane, sheet, !global);
            fmt::print("{} {} {}: lit plane pixels {}, falsely shadowed {}; sheet shadow pixels {}, falsely lit {}; "
                       "other material {}; pixels on an edge left out {} (a shadow's edge moved by the offset {})\n",
                       GetParam(), global ? "global" : "local", vulkan ? "vulkan" : "cpu", n.lit,
                       n.falsely_shadowed, n.occluder_shadow, n.falsely_lit, n.label_mismatches, n.unsure, n.moved);
            EXPECT_GT(n.lit, 1000u);
            EXPECT_EQ(n.falsely_shadowed, 0u);
            EXPECT_GE(n.occluder_shadow, 40u);
            EXPECT_EQ(n.falsely_lit, 0u);
            EXPECT_EQ(n.label_mismatches, 0u);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Stability, AcneAtScale,
                         ::testing::Values("case1_acne_scale1.json", "case1_acne_scale1e3.json",
                                           "case1_acne_scale1e5.json", "case3_far_from_origin.json",
                                           "case3_far_odd_offset.json"),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                             return param.param.substr(0, param.param.find('.'));
                         });

// -------------------------------------------- case 2: tiny and far, huge and near

struct MaskCounts {
    std::size_t band = 0;        // pixels within one pixel of the double mask's silhouette
    std::size_t mismatches = 0;  // pixels showing another material than the double mask
    std::size_t of_material = 0; // pixels of the object asked about (to know it is seen)
};

// The double mask at pixel centres against the material each pixel shows. The band:
// pixels whose mask differs from one of their 8 neighbours' (either side of an edge).
MaskCounts compare_mask(const Scene& s, const Image& image, int material) {
    const std::uint32_t w = s.camera.width, h = s.camera.height;
    std::vector<int> mask(std::size_t(w) * h);
    const dvec3 origin = flatten_scene(s).origin;
    for (std::uint32_t py = 0; py < h; ++py) {
        for (std::uint32_t px = 0; px < w; ++px) {
            mask[py * w + px] = expect_at(s, origin, px + 0.5, py + 0.5).material;
        }
    }
    MaskCounts n;
    for (std::uint32_t py = 0; py < h; ++py) {
        for (std::uint32_t px = 0; px < w; ++px) {
            const int m = mask[py * w + px];
            bool edge = false;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const int x = int(px) + dx, y = int(py) + dy;
                    if (x >= 0 && y >= 0 && x < int(w) && y < int(h)) edge = edge || mask[y * w + x] != m;
                }
            }
            n.band += edge ? 1 : 0;
            n.of_material += m == material ? 1 : 0;
            n.mismatches += seen_material(s, image, px, py) != m ? 1 : 0;
        }
    }
    return n;
}

// A sphere of radius 2^-10 at 1e4 from the camera: 1e-7 of its distance, a couple of
// float ULPs. Its coordinates are exact floats, so the mask measures the kernel's
// intersection arithmetic, not the scene's rounding to float.
TEST(TinyAndHugeSpheres, TinyFarSphereMatchesTheDoubleMask) {
    const Scene s = stability_scene("case2_tiny_far.json");
    for (bool vulkan : {false, true}) {
        const RenderOutcome out = vulkan ? test::render_vulkan(s) : test::render_cpu(s);
        test::expect_sane(out);
        const MaskCounts n = compare_mask(s, out.image, material_index(s, "ball"));
        fmt::print("case2_tiny_far {}: sphere pixels {}, band {}, mismatches {}\n", vulkan ? "vulkan" : "cpu",
                   n.of_material, n.band, n.mismatches);
        EXPECT_GT(n.of_material, 300u);
        EXPECT_GT(n.band, 50u);
        EXPECT_LE(double(n.mismatches), 0.005 * double(n.band));
    }
}

// The camera 1.5 above a sphere of radius 1e5, with a ball resting on it: the mask
// (ground, ball, sky beyond the horizon) matches the double one, and no lit ground
// pixel is shadowed. From the camera, dot(oc, oc) - r^2 is 3e5 out of 1e10, where
// float's ULP is 1024.
TEST(TinyAndHugeSpheres, HugeNearSphereMatchesTheDoubleMaskWithoutAcne) {
    const Scene s = stability_scene("case2_huge_near.json");
    const int ground = material_index(s, "ground");
    for (bool vulkan : {false, true}) {
        const RenderOutcome out = vulkan ? test::render_vulkan(s) : test::render_cpu(s);
        test::expect_sane(out);
        const MaskCounts mask = compare_mask(s, out.image, ground);
        const ShadowCounts n = count_shadows(s, out.image, ground, material_index(s, "ball"), true);
        fmt::print("case2_huge_near {}: ground pixels {}, band {}, mask mismatches {}; lit ground pixels {}, "
                   "falsely shadowed {}; ball shadow pixels {}, falsely lit {}\n",
                   vulkan ? "vulkan" : "cpu", mask.of_material, mask.band, mask.mismatches, n.lit,
                   n.falsely_shadowed, n.occluder_shadow, n.falsely_lit);
        EXPECT_GT(mask.band, 50u);
        EXPECT_LE(double(mask.mismatches), 0.005 * double(mask.band));
        EXPECT_GT(n.lit, 1000u);
        EXPECT_EQ(n.falsely_shadowed, 0u);
        EXPECT_GT(n.occluder_shadow, 20u);
        EXPECT_EQ(n.falsely_lit, 0u);
    }
}

// ------------------------------------------------- case 3: far from the origin

// The fraction of pixels whose 8-bit values agree in every channel, quantized as the
// PNG writer does: clamped, sRGB-encoded, rounded to 1/255 (host/image/image.cpp).
double same_8bit(const Image& a, const Image& b) {
    std::size_t same = 0;
    const std::size_t n = std::size_t(a.width) * a.height;
    auto byte = [](float v) { return std::lround(linear_to_srgb(v) * 255.0f); };
    for (std::size_t p = 0; p < n; ++p) {
        bool equal = true;
        for (int c = 0; c < 3; ++c) equal = equal && byte(a.rgb[3 * p + c]) == byte(b.rgb[3 * p + c]);
        same += equal ? 1 : 0;
    }
    return double(same) / double(n);
}

// Case 1's scene at scale 1, translated by (1e6, 1e6, 1e6), camera and light
// included: the same 8-bit image on at least 99.9% of pixels, with and without the
// grid, on both backends. Translated by an offset that is no multiple of 64, the eye
// lands elsewhere in the kernel's 64-grid (flatten/flat_scene.cpp), so kernel coordinates are
// up to 32 larger and so is the self-intersection offset; with this scene's light at a
// grazing 1/1000, the sheet's shadow edge moves by the offset times 1000: 99.28% of
// pixels equal, against 94.60% before camera-relative coordinates. AcneAtScale holds
// that translation to the double tracer like the others.
TEST(FarFromOrigin, TranslatedSceneRendersTheSame8BitImage) {
    for (const char* far : {"case3_far_from_origin.json", "case3_far_odd_offset.json"}) {
        const double required = std::string(far) == "case3_far_from_origin.json" ? 0.999 : 0.99;
        for (GridMode grid : {GridMode::Auto, GridMode::On}) {
            Scene near_scene = stability_scene("case1_acne_scale1.json");
            Scene far_scene = stability_scene(far);
            near_scene.render.grid.mode = far_scene.render.grid.mode = grid;
            for (bool vulkan : {false, true}) {
                SCOPED_TRACE(fmt::format("{}, grid {}, {}", far, grid == GridMode::On ? "on" : "auto",
                                         vulkan ? "vulkan" : "cpu"));
                const RenderOutcome a = vulkan ? test::render_vulkan(near_scene) : test::render_cpu(near_scene);
                const RenderOutcome b = vulkan ? test::render_vulkan(far_scene) : test::render_cpu(far_scene);
                test::expect_sane(a);
                test::expect_sane(b);
                EXPECT_EQ(a.stats.grid.used, b.stats.grid.used);
                const double same = same_8bit(a.image, b.image);
                fmt::print("{} grid {} {}: same 8-bit pixels {:.4f}%\n", far, grid == GridMode::On ? "on" : "auto",
                           vulkan ? "vulkan" : "cpu", 100.0 * same);
                EXPECT_GE(same, required);
            }
        }
    }
}

}  // namespace
}  // namespace vkrt
