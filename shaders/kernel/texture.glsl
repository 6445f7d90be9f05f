// Colour textures (HAS_TEXTURES): a material's colour times the texture's value at
// the hit's texture coordinates, by bilinear filtering of linear texels. 8-bit
// texels are decoded here, by the same float arithmetic on both backends (a
// multiplication by the float nearest 1/255, or a look-up in the sRGB table the
// host computed), so a textured image is the same on both. No mipmaps: a pixel's
// samples are jittered over its area, so the average over many samples filters the
// texture as it filters edges (tests/kernel/texture_test.cpp shows a checkerboard at a
// distance).

uint texture_format(Texture t) {
    return (t.info.w >> 4u) & 3u;
}

// The linear value of an sRGB-encoded byte.
float srgb_byte(uint b) {
    return uintBitsToFloat(load_table_word(b));
}

// Texel (x, y) of texture t, x and y already wrapped, linear. (One return: SPIRV-Tools
// leaves calls of functions with early returns uninlined in places.)
vec4 texel_at(Texture t, uint x, uint y) {
    uint i = y * t.info.y + x;
    vec4 c;
    if (texture_format(t) == TEXEL_HALF) {
        uint w = t.info.x + 2u * i;
        c = vec4(unpackHalf2x16(load_texture_word(w)), unpackHalf2x16(load_texture_word(w + 1u)));
    } else {
        uint word = load_texture_word(t.info.x + i);
        uint r = word & 255u;
        uint g = (word >> 8u) & 255u;
        uint b = (word >> 16u) & 255u;
        float a = float(word >> 24u) * (1.0f / 255.0f);
        if ((t.info.w & TEXTURE_SRGB_BIT) != 0u) {
            c = vec4(srgb_byte(r), srgb_byte(g), srgb_byte(b), a);
        } else {
            c = vec4(float(r) * (1.0f / 255.0f), float(g) * (1.0f / 255.0f), float(b) * (1.0f / 255.0f), a);
        }
    }
    return c;
}

// Texel index i, from -1 to 2n, on an axis of n texels, by the wrap mode. (GLSL
// leaves % of negative numbers undefined: a period is added first.) This and
// wrap_coordinate have one return, no early exit, as texel_at: such functions the
// host inlines (host/gpu/spirv_specialize.cpp), and every texture lookup calls them.
uint wrap_index(int i, uint n, uint mode) {
    int size = int(n);
    uint index = 0u;
    if (mode == WRAP_CLAMP) {
        index = uint(clamp(i, 0, size - 1));
    } else if (mode == WRAP_MIRROR) {
        int m = (i + 2 * size) % (2 * size);
        index = uint(m < size ? m : 2 * size - 1 - m);
    } else {
        index = uint((i + size) % size);
    }
    return index;
}

// A texture coordinate brought into [0, 2], where repeat and mirror (both periodic
// with 2) and clamp give what they give at the coordinate itself; not finite or
// beyond 1e30 (where floats have no fraction left): 0.
float wrap_coordinate(float c, uint mode) {
    float w = 0.0f;
    if (abs(c) < 1.0e30f) {
        w = mode == WRAP_CLAMP ? clamp(c, 0.0f, 1.0f) : clamp(c - 2.0f * floor(c * 0.5f), 0.0f, 2.0f);
    }
    return w;
}

// The texture's value at (u, v): (0, 0) is the top left corner of the image, (1, 1)
// the bottom right; the four texels around the point weighed by its distance from
// their centres.
vec4 texture_bilinear(Texture t, vec2 uv) {
    uint wrap_s = t.info.w & 3u;
    uint wrap_t = (t.info.w >> 2u) & 3u;
    vec2 x = vec2(wrap_coordinate(uv.x, wrap_s) * float(t.info.y), wrap_coordinate(uv.y, wrap_t) * float(t.info.z)) -
             vec2(0.5f);
    vec2 f0 = floor(x);
    vec2 f = x - f0;
    int x0 = int(f0.x);
    int y0 = int(f0.y);
    uint xa = wrap_index(x0, t.info.y, wrap_s);
    uint xb = wrap_index(x0 + 1, t.info.y, wrap_s);
    uint ya = wrap_index(y0, t.info.z, wrap_t);
    uint yb = wrap_index(y0 + 1, t.info.z, wrap_t);
    vec4 top = mix(texel_at(t, xa, ya), texel_at(t, xb, ya), f.x);
    vec4 bottom = mix(texel_at(t, xa, yb), texel_at(t, xb, yb), f.x);
    return mix(top, bottom, f.y);
}

// Texture coordinates through the material's transform (Material.uv_u, uv_v).
vec2 material_uv(Material m, vec2 uv) {
    return vec2(dot(vec2(m.uv_u), uv) + m.uv_u.z, dot(vec2(m.uv_v), uv) + m.uv_v.z);
}

// Texture coordinates through the material's second transform (Material.uv2_u, uv2_v).
vec2 second_material_uv(Material m, vec2 uv) {
    return vec2(dot(vec2(m.uv2_u), uv) + m.uv2_u.z, dot(vec2(m.uv2_v), uv) + m.uv2_v.z);
}

// Whether material m's texture in `slot` (MAP_<slot>, constants.glsl) reads the
// second mapping.
bool on_second_mapping(Material m, uint slot) {
    return HAS_SECOND_MAPPING && (m.second_maps & (1u << slot)) != 0u;
}

// The coordinates a material's textures read at a point of a triangle or quad: the
// first mapping's (the triangle's coordinates through the material's transform) and
// the second's (the triangle's second coordinates, or where the material says so
// its first, through the second transform; the first's without HAS_SECOND_MAPPING).
// glTF gives each texture its own TEXCOORD_<n> and KHR_texture_transform; vkrt keeps
// two mappings a material (docs/gltf.md).
struct TextureCoords {
    vec2 first;
    vec2 second;
};

// The coordinates at the point of weights bary on triangle `index` of material m,
// whose first coordinates there are uv (triangle_uv).
TextureCoords texture_coords(Material m, uint index, vec2 bary, vec2 uv) {
    TextureCoords c;
    c.first = material_uv(m, uv);
    c.second = c.first;
    if (HAS_SECOND_MAPPING && m.second_maps != 0u) {
        c.second = second_material_uv(m, m.second_coords != 0u ? second_uv(index, bary) : uv);
    }
    return c;
}

// The coordinates at a hit on any shape; only triangles and quads have second ones.
TextureCoords hit_texture_coords(Material m, Hit hit) {
    TextureCoords c;
    c.first = material_uv(m, hit.uv);
    c.second = c.first;
    if (HAS_SECOND_MAPPING && m.second_maps != 0u && (hit.prim >> REF_KIND_SHIFT) == REF_TRIANGLE) {
        c = texture_coords(m, hit.prim & REF_INDEX_MASK, hit.bary, hit.uv);
    }
    return c;
}

// The coordinates the texture in `slot` reads.
vec2 slot_uv(Material m, TextureCoords c, uint slot) {
    return on_second_mapping(m, slot) ? c.second : c.first;
}

// Corner k (0 to 2) of triangle `index` (record tri) as the texture in `slot` reads
// it: through the mapping that texture reads.
vec2 slot_corner_uv(Material m, Triangle tri, uint index, uint k, uint slot) {
    vec2 uv = material_uv(m, triangle_uv_corner(tri, k));
    if (on_second_mapping(m, slot)) {
        uv = second_material_uv(m, m.second_coords != 0u ? second_uv_corner(index, k) : triangle_uv_corner(tri, k));
    }
    return uv;
}

// An emission texture's radiance at (u, v): the emission times the texture.
vec3 textured_emission(Material m, vec2 uv) {
    return m.emission * vec3(texture_bilinear(load_texture(m.emission_map - 1u), uv));
}

// The share of material m that is glass: for a metallic-roughness material its
// dielectric's transmission, transmission (1 - metallic); 0 for the paper's
// material, whose glass is its `transmit` colour, and wherever glass is compiled out.
float glass_share(Material m) {
    return HAS_REFRACTION && HAS_MICROFACET && m.ggx_alpha > 0.0f ? m.transmission * (1.0f - m.metallic) : 0.0f;
}

// A metallic-roughness material's lobes from its base colour, metallic and roughness
// (flat_scene.cpp builds an untextured material's alike). Its glass (lobes/glass.glsl)
// takes glass_share = transmission (1 - metallic) of it, the other lobes the rest:
// the metal's share of those is metallic / (1 - glass_share), so that the metal keeps
// its share of the whole, and the dielectric reflects dielectric_f0 at normal
// incidence (with HAS_DIELECTRIC_SPECULAR, dielectric_f0_rgb, and dielectric_f90 at
// grazing incidence).
void set_metallic_roughness(INOUT(Material) m, vec3 base, float metallic, float roughness) {
    m.metallic = metallic;
    float glass = glass_share(m);
    float metal = glass > 0.0f ? (glass < 1.0f ? metallic / (1.0f - glass) : 0.0f) : metallic;
    m.diffuse = (1.0f - metal) * base;
    m.kd = 1.0f;
    m.ggx_f0 = mix(HAS_DIELECTRIC_SPECULAR ? m.dielectric_f0_rgb : vec3(m.dielectric_f0), base, metal);
    m.ggx_f90 = HAS_DIELECTRIC_SPECULAR ? mix(m.dielectric_f90, 1.0f, metal) : 1.0f;
    m.ggx_alpha = max(roughness * roughness, MIN_GGX_ALPHA);
    m.transmit = glass * base;
}

// The layers' textures at texture coordinates c (texture_coords): the coat's factor
// times the coat texture's red, its roughness times the coat roughness texture's
// green; the sheen's colour times the sheen colour texture, its roughness times the
// sheen roughness texture's alpha (glTF's packings). A width is the roughness
// squared, floored: the floor times the texture's square is below the floor, so
// scaling the stored width is scaling the roughness.
void apply_layer_textures(INOUT(Material) m, TextureCoords c) {
    if (HAS_COAT && m.coat_map != 0u) {
        m.coat = clamp(m.coat * texture_bilinear(load_texture(m.coat_map - 1u), slot_uv(m, c, MAP_COAT)).r, 0.0f, 1.0f);
    }
    if (HAS_COAT && m.coat_rough_map != 0u) {
        float g = clamp(texture_bilinear(load_texture(m.coat_rough_map - 1u), slot_uv(m, c, MAP_COAT_ROUGH)).g, 0.0f,
                        1.0f);
        m.coat_alpha = max(m.coat_alpha * (g * g), MIN_GGX_ALPHA);
    }
    if (HAS_SHEEN && m.sheen_map != 0u) {
        m.sheen_color = clamp(m.sheen_color * vec3(texture_bilinear(load_texture(m.sheen_map - 1u), slot_uv(m, c, MAP_SHEEN))),
                              vec3(0.0f), vec3(1.0f));
    }
    if (HAS_SHEEN && m.sheen_rough_map != 0u) {
        float a = clamp(texture_bilinear(load_texture(m.sheen_rough_map - 1u), slot_uv(m, c, MAP_SHEEN_ROUGH)).a, 0.0f,
                        1.0f);
        m.sheen_alpha = max(m.sheen_alpha * (a * a), MIN_SHEEN_ALPHA);
    }
}

// The specular textures at texture coordinates c (texture_coords): the specular
// factor (dielectric_f90) times the specular texture's alpha, the specular colour
// times the colour texture, and the dielectric's reflectance at normal incidence
// rebuilt from them as flat_scene.cpp builds it, min(f0 colour, 1) factor
// (KHR_materials_specular). set_metallic_roughness then mixes them with the metal's.
void apply_specular_textures(INOUT(Material) m, TextureCoords c) {
    float strength = m.dielectric_f90;
    vec3 color = m.specular_color;
    if (m.specular_map != 0u) {
        strength = clamp(strength * texture_bilinear(load_texture(m.specular_map - 1u), slot_uv(m, c, MAP_SPECULAR)).a,
                         0.0f, 1.0f);
    }
    if (m.specular_color_map != 0u) {
        color = max(color * vec3(texture_bilinear(load_texture(m.specular_color_map - 1u), slot_uv(m, c, MAP_SPECULAR_COLOR))),
                    vec3(0.0f));
    }
    m.dielectric_f0_rgb = min(vec3(m.dielectric_f0) * color, vec3(1.0f)) * strength;
    m.dielectric_f90 = strength;
}

// What multiplies a material's colour at a hit on a triangle: its colour texture
// (white without one) times, where `tinted`, the triangle's vertex colour.
vec3 surface_tint(Material m, Hit hit, TextureCoords coords, bool tinted) {
    vec3 c = HAS_TEXTURES && m.color_map != 0u ? vec3(texture_bilinear(load_texture(m.color_map - 1u), coords.first))
                                               : vec3(1.0f);
    if (tinted) {
        c = c * vec3(vertex_color(hit.prim & REF_INDEX_MASK, hit.bary));
    }
    return c;
}

// The base colour at a hit, for the albedo pass (HAS_PASSES): a metallic-roughness
// material's base colour, the paper's material's diffuse colour, either times the
// colour texture and vertex colours as surface_material applies them.
vec3 surface_base_colour(Hit hit) {
    Material m = load_material(hit.material);
    vec3 base = m.ggx_alpha > 0.0f ? m.base_color : m.diffuse;
    bool triangle = (hit.prim >> REF_KIND_SHIFT) == REF_TRIANGLE;
    bool tinted = HAS_VERTEX_COLORS && triangle && triangle_has_colors(hit.prim & REF_INDEX_MASK);
    if ((HAS_TEXTURES && triangle && m.color_map != 0u) || tinted) {
        base = base * surface_tint(m, hit, hit_texture_coords(m, hit), tinted);
    }
    return base;
}

// The material at a hit, textured. A Phong material's diffuse colour times the
// colour texture; a metallic-roughness material rebuilt from its factors (flat_scene.cpp)
// times its textures: base colour times the colour texture, metallic times the
// metallic-roughness texture's blue channel, roughness times its green (glTF's
// packing), transmission times the transmission texture's red; the emission times
// the emission texture; the layers' and the specular textures as
// apply_layer_textures and apply_specular_textures say. Vertex colours multiply the
// colour as the colour texture does (vertex_data.glsl). Only triangles and quads
// have texture coordinates and vertex colours; other shapes keep the untextured
// material.
Material surface_material(Hit hit) {
    Material m = load_material(hit.material);
    bool triangle = (hit.prim >> REF_KIND_SHIFT) == REF_TRIANGLE;
    TextureCoords coords = hit_texture_coords(m, hit);
    if (HAS_TEXTURES && m.emission_map != 0u && triangle) {
        m.emission = textured_emission(m, slot_uv(m, coords, MAP_EMISSION));
    }
    if (HAS_TEXTURES && (HAS_COAT || HAS_SHEEN) && triangle &&
        (m.coat_map != 0u || m.coat_rough_map != 0u || m.sheen_map != 0u || m.sheen_rough_map != 0u)) {
        apply_layer_textures(m, coords);
    }
    bool specular_textured = HAS_DIELECTRIC_SPECULAR && (m.specular_map != 0u || m.specular_color_map != 0u);
    bool textured = HAS_TEXTURES && triangle &&
                    (m.color_map != 0u || m.metal_rough_map != 0u || m.transmission_map != 0u || specular_textured);
    bool tinted = HAS_VERTEX_COLORS && triangle && triangle_has_colors(hit.prim & REF_INDEX_MASK);
    if (textured || tinted) {
        vec3 c = surface_tint(m, hit, coords, tinted);
        if (m.ggx_alpha > 0.0f) {
            vec3 base = m.base_color * c;
            float metallic = m.metallic;
            float roughness = m.roughness;
            if (HAS_TEXTURES && m.metal_rough_map != 0u) {
                vec4 mr = texture_bilinear(load_texture(m.metal_rough_map - 1u), slot_uv(m, coords, MAP_METAL_ROUGH));
                metallic = clamp(metallic * mr.b, 0.0f, 1.0f);
                roughness = clamp(roughness * mr.g, 0.0f, 1.0f);
            }
            if (HAS_TEXTURES && m.transmission_map != 0u) {
                vec4 t = texture_bilinear(load_texture(m.transmission_map - 1u), slot_uv(m, coords, MAP_TRANSMISSION));
                m.transmission = clamp(m.transmission * t.r, 0.0f, 1.0f);
            }
            if (HAS_TEXTURES && specular_textured) {
                apply_specular_textures(m, coords);
            }
            set_metallic_roughness(m, base, metallic, roughness);
        } else {
            m.diffuse = m.diffuse * c;
        }
    }
    return m;
}
