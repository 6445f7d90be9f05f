// Primary rays. The host builds the camera vectors in double precision
// (host/flatten/flat_scene.cpp); the kernel only combines them.

// Shirley and Chiu's concentric map of the unit square onto the unit disc ("A
// Low Distortion Map Between Disk and Square", 1997): squares around the centre
// become rings and the square's strata stay compact on the disc, so stratified
// points stay stratified.
vec2 concentric_disc(vec2 u) {
    vec2 a = 2.0f * u - 1.0f;
    if (a.x == 0.0f && a.y == 0.0f) {
        return vec2(0.0f);
    }
    bool wide = abs(a.x) > abs(a.y);
    float r = wide ? a.x : a.y;
    float phi = wide ? (0.25f * PI) * (a.y / a.x) : 0.5f * PI - (0.25f * PI) * (a.x / a.y);
    vec2 sc = sin_cos(phi);
    return r * vec2(sc.y, sc.x);
}

// The pinhole's ray through continuous image position (x, y), in pixels from the
// top-left corner of the image (row 0 at the top): from the eye, or the lens's centre.
// The direction through (x, y), one unit long along the view axis.
vec3 camera_direction(float x, float y) {
    precise vec3 d = camera_corner() + x * camera_right() + y * camera_down();
    return d;
}

Ray camera_ray(float x, float y) {
    vec3 d = camera_direction(x, y);
    // unit_vector (ray.glsl), not normalize(): both backends then start every eye ray
    // bit-identical, which matters where mirrors amplify an ULP (a sphereflake's
    // crevices, reflection after reflection, flipped whole pixels at depth 5 before;
    // gallery image I).
    return Ray(camera_eye(), unit_vector(d));
}

// The same through a thin lens (HAS_LENS): the ray leaves the point `lens` in [0, 1)^2
// maps to on the lens disc and passes through the pinhole ray's point on the plane in
// focus, so that plane stays sharp and the rest blurs with its distance from it.
Ray camera_ray(float x, float y, vec2 lens) {
    if (!(HAS_LENS && lens_scale() > 0.0f)) {
        return camera_ray(x, y);
    }
    vec3 d = camera_direction(x, y);
    // camera_right() and camera_down() are a pixel long, lens_scale() is the lens
    // radius in pixels; d is 1 long along the view axis, so focus_distance() * d lies
    // on the plane in focus.
    vec2 disc = lens_scale() * concentric_disc(lens);
    precise vec3 offset = disc.x * camera_right() + disc.y * camera_down();
    precise vec3 dir = focus_distance() * d - offset;
    return Ray(camera_eye() + offset, unit_vector(dir));
}

// The lens point of a sample (its own slot), when there is a lens.
vec2 lens_position(INOUT(Rng) rng) {
    if (!HAS_LENS) {
        return vec2(0.5f);
    }
    rng_seek(rng, SLOT_LENS);
    return rng_2d(rng);
}

// Position inside the pixel for one sample: sample k covers sub-pixel k mod aa^2 of
// the paper's regular aa x aa grid (Fig. 6), at the sub-pixel's centre, or at a
// uniformly random point inside it when jitter is on (the camera's slot, rng.glsl).
vec2 subpixel_position(uint sample_index, INOUT(Rng) rng) {
    uint aa = aa_per_side();
    uint k = sample_index % (aa * aa);
    vec2 jitter = vec2(0.5f);
    if (HAS_JITTER) {
        rng_seek(rng, SLOT_CAMERA);
        jitter = rng_2d(rng);
    }
    return vec2((float(k % aa) + jitter.x) / float(aa), (float(k / aa) + jitter.y) / float(aa));
}
