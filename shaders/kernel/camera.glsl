// Primary rays. The host builds the camera vectors in double precision
// (host/flatten/flat_scene.cpp); the kernel only combines them.

// The ray through continuous image position (x, y), in pixels from the top-left
// corner of the image (row 0 at the top).
Ray camera_ray(float x, float y) {
    precise vec3 d = camera_corner() + x * camera_right() + y * camera_down();
    // unit_vector (ray.glsl), not normalize(): both backends then start every eye ray
    // bit-identical, which matters where mirrors amplify an ULP (a sphereflake's
    // crevices, reflection after reflection, flipped whole pixels at depth 5 before;
    // gallery image I).
    return Ray(camera_eye(), unit_vector(d));
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
