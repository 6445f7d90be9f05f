#include "scene/scene_gpu.hpp"

#include "scene/vec_math.hpp"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace vkrt {
namespace {

using kernel::uvec4;
using kernel::vec4;

vec4 to_vec4(const dvec3& v, double w = 0.0) {
    return vec4(static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z),
                static_cast<float>(w));
}

// The camera frame is built in double and rounded once, so the kernel's rays do not
// inherit the error of a float cross product and tan().
void set_camera(const Camera& cam, kernel::Params& p) {
    const dvec3 forward = robust_normalize(cam.look_at - cam.eye);
    const dvec3 right = glm::normalize(glm::cross(forward, robust_normalize(cam.up)));
    const dvec3 up = glm::cross(right, forward);
    const double pixel = 2.0 * std::tan(glm::radians(cam.fov) / 2.0) / cam.height;
    const dvec3 step_right = right * pixel;
    const dvec3 step_down = -up * pixel;
    const dvec3 corner = forward - step_right * (cam.width / 2.0) - step_down * (cam.height / 2.0);
    p.cam_eye = to_vec4(cam.eye);
    p.cam_corner = to_vec4(corner);
    p.cam_right = to_vec4(step_right);
    p.cam_down = to_vec4(step_down);
}

kernel::Material flatten(const Material& m) {
    return kernel::Material(to_vec4(m.diffuse, m.kd), to_vec4(m.specular, m.ks),
                            to_vec4(m.reflect, m.shininess), to_vec4(m.transmit, m.ior),
                            to_vec4(m.emission));
}

kernel::Triangle flatten(const Triangle& t) {
    kernel::Triangle out{};
    out.p0 = to_vec4(t.vertices[0]);
    out.p1 = to_vec4(t.vertices[1]);
    out.p2 = to_vec4(t.vertices[2]);
    if (t.normals) {
        out.n0 = to_vec4((*t.normals)[0]);
        out.n1 = to_vec4((*t.normals)[1]);
        out.n2 = to_vec4((*t.normals)[2]);
    }
    out.meta = uvec4(t.material, t.normals ? 1u : 0u, 0u, 0u);
    return out;
}

template <class T>
std::size_t bytes(const std::vector<T>& v) { return v.size() * sizeof(T); }

}  // namespace

std::vector<BufferSize> SceneGpu::built_buffers() const {
    std::vector<BufferSize> out;
    auto add = [&](const char* name, std::size_t size) {
        if (size != 0) out.push_back({name, size});
    };
    add("materials", bytes(materials));
    add("spheres", bytes(spheres));
    add("triangles", bytes(triangles));
    add("point_lights", bytes(lights));
    return out;
}

SceneGpu build_scene_gpu(const Scene& scene) {
    SceneGpu g;
    g.features = analyze_features(scene);
    const RenderSettings& r = scene.render;
    g.samples_per_pixel = r.samples_per_pixel();

    kernel::Params& p = g.params;
    set_camera(scene.camera, p);
    p.ambient = to_vec4(r.ambient);
    p.background = to_vec4(r.background);
    p.image = uvec4(scene.camera.width, scene.camera.height, r.aa, r.seed);
    p.limits = uvec4(r.loop_budget != 0 ? r.loop_budget : kernel::DEFAULT_LOOP_BUDGET, r.max_depth, 0u, 0u);

    // Buffers only the left-out features read are not built (and so not uploaded).
    const bool any_geometry = !scene.spheres.empty() || !scene.triangles.empty();
    if (any_geometry) {
        for (const Material& m : scene.materials) g.materials.push_back(flatten(m));
    }
    if (g.features.has(Feature::HAS_SPHERES)) {
        for (const Sphere& s : scene.spheres) {
            g.spheres.push_back(kernel::Sphere(to_vec4(s.center, s.radius), uvec4(s.material, 0u, 0u, 0u)));
        }
    }
    if (g.features.has(Feature::HAS_TRIANGLES)) {
        for (const Triangle& t : scene.triangles) g.triangles.push_back(flatten(t));
    }
    if (g.features.has(Feature::HAS_POINT_LIGHTS)) {
        for (const PointLight& l : scene.lights) {
            g.lights.push_back(kernel::PointLight(to_vec4(l.position), to_vec4(l.color * l.intensity)));
        }
    }
    p.counts = uvec4(g.spheres.size(), g.triangles.size(), g.lights.size(), g.materials.size());
    return g;
}

}  // namespace vkrt
