// The material record, one field a line, in the order of its lanes: both languages
// declare layout.glsl's Material from this list, render.comp assembles it from the
// scene buffer's texels by it, and host/kernel/types.hpp checks that each field sits
// at its texel and lane. A field is named for the one thing it holds; a lane that
// holds nothing is a MATERIAL_PAD, written as 0.
//
//   MATERIAL_FIELD(type, name, texel, lane)   a uint or float in lane x, y, z or w
//   MATERIAL_FIELD3(type, name, texel)        a vec3 in lanes xyz of a texel
//   MATERIAL_PAD(texel, lane)                 an unused lane
//
// The file that includes this one defines the three macros; they are undefined at
// the end. The materials of the scene file (docs/scene-format.md) map onto these as
// host/flatten/flat_scene.cpp says.

// The paper's material (and the lobes global mode builds from it, bsdf.glsl).
MATERIAL_FIELD3(vec3, diffuse, 0)      // diffuse colour
MATERIAL_FIELD(float, kd, 0, w)        // its weight
MATERIAL_FIELD3(vec3, specular, 1)     // Phong highlight colour
MATERIAL_FIELD(float, ks, 1, w)        // its weight
MATERIAL_FIELD3(vec3, mirror, 2)       // mirror reflectance (the scene file's `reflect`)
MATERIAL_FIELD(float, shininess, 2, w) // Phong exponent
MATERIAL_FIELD3(vec3, transmit, 3)     // glass transmittance
MATERIAL_FIELD(float, ior, 3, w)       // index of refraction
MATERIAL_FIELD3(vec3, emission, 4)     // emitted radiance, front face only
MATERIAL_FIELD(uint, fresnel, 4, w)    // 1: mirror and glass split by Fresnel; 0: by the constant weights

// The metallic-roughness material's GGX lobe (lobes/ggx.glsl), built from its
// factors on the host and rebuilt per hit when textured (texture.glsl).
MATERIAL_FIELD3(vec3, ggx_f0, 5)       // reflectance at normal incidence
MATERIAL_FIELD(float, ggx_alpha, 5, w) // GGX width; 0: no such lobe

// Textures: 1 + the texture's index (texture.glsl), 0 for none.
MATERIAL_FIELD(uint, color_map, 6, x)           // multiplies the diffuse colour or the base colour
MATERIAL_FIELD(uint, metal_rough_map, 6, y)     // metallic (blue) and roughness (green)
MATERIAL_FIELD(uint, normal_map, 6, z)          // normal_map.glsl
MATERIAL_FIELD(uint, emission_map, 6, w)        // multiplies the emission

// The texture coordinates' transform: u' = dot(uv_u.xy, uv) + uv_u.z, v' likewise.
MATERIAL_FIELD3(vec3, uv_u, 7)
MATERIAL_FIELD(float, metallic, 7, w)  // the metallic-roughness factors (0 for the paper's material)
MATERIAL_FIELD3(vec3, uv_v, 8)
MATERIAL_FIELD(float, roughness, 8, w)
MATERIAL_FIELD3(vec3, base_color, 9)   // the metallic-roughness base colour
MATERIAL_FIELD(float, transmission, 9, w) // the share of its dielectric that is glass (glTF's transmission)

// Coverage (alpha.glsl): glTF's alphaMode. The opacity at a point is `alpha` times
// the colour texture's alpha there.
MATERIAL_FIELD(uint, alpha_mode, 10, x)    // ALPHA_OPAQUE, ALPHA_MASK or ALPHA_BLEND
MATERIAL_FIELD(float, alpha, 10, y)        // the opacity factor (glTF's base colour alpha)
MATERIAL_FIELD(float, alpha_cutoff, 10, z) // ALPHA_MASK: opaque where the opacity is at least this
// The GGX lobe's reflectance at grazing incidence (HAS_DIELECTRIC_SPECULAR; 1 without):
// the metal's 1 and the dielectric's specular factor mixed as ggx_f0 is.
MATERIAL_FIELD(float, ggx_f90, 10, w)

// Glass of a metallic-roughness material (lobes/glass.glsl): the dielectric's
// reflectance at normal incidence, from its index of refraction (glTF's
// KHR_materials_ior), and whether the glass is a thin wall that light crosses
// without turning (glTF's transmission without KHR_materials_volume).
MATERIAL_FIELD(float, dielectric_f0, 11, x)
MATERIAL_FIELD(uint, thin_walled, 11, y)  // 1: transmitted light goes on straight; 0: it refracts

// A clear coat over the metallic-roughness material (lobes/coat.glsl; glTF's
// KHR_materials_clearcoat): its factor (0: none) and its GGX width.
MATERIAL_FIELD(float, coat, 11, z)
MATERIAL_FIELD(float, coat_alpha, 11, w)

// What the glass absorbs inside (glTF's KHR_materials_volume): the attenuation
// coefficient per unit length of world space, per channel, -ln(attenuationColor) /
// attenuationDistance; 0 for a clear medium (lobes/glass.glsl, medium_transmittance).
MATERIAL_FIELD3(vec3, attenuation, 12)
// A texture whose red channel multiplies the transmission (glTF's
// transmissionTexture): 1 + its index, 0 for none (texture.glsl).
MATERIAL_FIELD(uint, transmission_map, 12, w)

// Sheen over the metallic-roughness material (lobes/sheen.glsl; glTF's
// KHR_materials_sheen): its colour (0: none) and the width of its distribution.
MATERIAL_FIELD3(vec3, sheen_color, 13)
MATERIAL_FIELD(float, sheen_alpha, 13, w)

// The dielectric's reflectance with glTF's KHR_materials_specular (HAS_DIELECTRIC_SPECULAR):
// at normal incidence min(dielectric_f0 * specular colour, 1) * specular factor, at
// grazing incidence the specular factor; texture.glsl mixes them with the metal's.
MATERIAL_FIELD3(vec3, dielectric_f0_rgb, 14)
MATERIAL_FIELD(float, dielectric_f90, 14, w)

// The layers' textures (texture.glsl; glTF's KHR_materials_clearcoat and _sheen): 1 +
// the texture's index, 0 for none. Red multiplies the coat's factor, green its
// roughness; the colour multiplies the sheen's colour, alpha its roughness.
MATERIAL_FIELD(uint, coat_map, 15, x)
MATERIAL_FIELD(uint, coat_rough_map, 15, y)
MATERIAL_FIELD(uint, sheen_map, 15, z)
MATERIAL_FIELD(uint, sheen_rough_map, 15, w)

// The clear coat's own normal map (normal_map.glsl coat_normal; glTF's
// clearcoatNormalTexture): 1 + the texture's index, 0 for none (the coat then lies on
// the surface's normal, not the base's mapped one).
MATERIAL_FIELD(uint, coat_normal_map, 16, x)

// The dielectric's specular textures (texture.glsl apply_specular_textures; glTF's
// specularTexture, whose alpha multiplies the specular factor, and
// specularColorTexture, which multiplies the specular colour): 1 + the texture's
// index, 0 for none; and that colour, which dielectric_f0_rgb holds multiplied in.
MATERIAL_FIELD(uint, specular_map, 16, y)
MATERIAL_FIELD(uint, specular_color_map, 16, z)

// A second mapping of texture coordinates (texture.glsl, HAS_SECOND_MAPPING): the
// textures whose bit 1 << MAP_<slot> second_maps has read at it (0: none), through
// the transform uv2_u, uv2_v (as uv_u, uv_v), from the triangle's second coordinates
// (vertex_data.glsl, second_uv) where second_coords is 1, else from its first.
MATERIAL_FIELD(uint, second_maps, 16, w)
MATERIAL_FIELD3(vec3, specular_color, 17)
MATERIAL_FIELD(uint, second_coords, 17, w)
MATERIAL_FIELD3(vec3, uv2_u, 18)
MATERIAL_PAD(18, w)
MATERIAL_FIELD3(vec3, uv2_v, 19)
MATERIAL_PAD(19, w)

#undef MATERIAL_PAD
#undef MATERIAL_FIELD3
#undef MATERIAL_FIELD
