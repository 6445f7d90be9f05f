// The mirror lobe: a delta lobe that reflects `reflect` of the light into the mirror
// direction, in local mode's ray tree (sample.glsl) and global mode's paths
// (global.glsl, scatter_delta). `n` is the unit shading normal on the side the ray
// arrives from (Hit.normal), `d` the unit direction of the arriving ray.

// Renormalized: d and n are unit only to rounding, and the error would compound over
// a chain of mirrors.
vec3 mirror_direction(vec3 d, vec3 n) {
    precise vec3 r = d - (2.0f * dot(d, n)) * n;
    return unit_vector(r);
}

struct MirrorLobe {
    vec3 color;    // reflect (0 without HAS_REFLECTION)
    float weight;  // the mean of its colour
};

MirrorLobe mirror_lobe(Material m) {
    MirrorLobe l;
    l.color = HAS_REFLECTION ? m.mirror : vec3(0.0f);
    l.weight = mean3(l.color);
    return l;
}
