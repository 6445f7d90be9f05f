#include "bench/random_spheres.hpp"

#include <cmath>

#include <fmt/format.h>

namespace vkrt::bench {

std::string random_spheres_scene(std::uint64_t count) {
    // h_random_spheres.json's cube, camera, light and radii at 100,000 spheres
    // ([0.005, 0.02]), the radii scaled by (100,000 / count)^(1/3) elsewhere: about
    // 14% of the cube is filled at every count. No ground quad, so the primitive
    // count is the sphere count; at 100,000 the spheres are that scene's own.
    const double scale = std::cbrt(100000.0 / double(count));
    return fmt::format(R"({{
  "camera": {{ "eye": [3.1, 2.3, 4.1], "look_at": [0, -0.2, 0], "fov": 38, "width": 512, "height": 512 }},
  "render": {{ "shadows": true, "ambient": [0.06, 0.06, 0.07], "background": [0.02, 0.02, 0.03] }},
  "materials": {{
    "red":   {{ "diffuse": [0.8, 0.2, 0.15], "specular": [1, 1, 1], "ks": 0.4, "shininess": 50 }},
    "gold":  {{ "diffuse": [0.85, 0.65, 0.2], "specular": [1, 0.9, 0.6], "ks": 0.5, "shininess": 80 }},
    "blue":  {{ "diffuse": [0.2, 0.35, 0.85], "specular": [1, 1, 1], "ks": 0.3, "shininess": 30 }},
    "white": {{ "diffuse": [0.85, 0.85, 0.85] }}
  }},
  "lights": [ {{ "type": "point", "position": [-3, 6, 4], "intensity": 1.0 }} ],
  "objects": [
    {{ "type": "random_spheres", "count": {}, "seed": 1, "min": [-1, -1, -1], "max": [1, 1, 1],
      "radius": [{:.9g}, {:.9g}], "materials": ["red", "gold", "blue", "white"] }}
  ]
}}
)",
                       count, 0.005 * scale, 0.02 * scale);
}

}  // namespace vkrt::bench
