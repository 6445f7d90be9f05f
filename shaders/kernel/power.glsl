// The kernel's own x^y for x in [0, 1] and y >= 0 (the Phong lobe's cos^n, and the
// n-th root that samples it), from additions, multiplications, divisions and bit
// operations only, each rounded once: for the reason of trig.glsl. Vulkan's built-in
// pow is exp2(y log2 x) with an error of several ULP that grows with y log2 x, and
// lavapipe's and the C library's differ in their last bits; at a Phong exponent of
// 200 that put 22 of 3,072 pixels of scenes/convergence/glossy.json more than 1e-5
// apart between the backends.

// log2(x) for a finite x > 0: x = m 2^e with m in [sqrt(1/2), sqrt(2)), and log2(m) =
// (2 / ln 2) atanh(t) with t = (m - 1) / (m + 1), |t| < 0.172, whose series t + t^3/3
// + ... to t^11 leaves out less than 1e-9 of it. Denormal x is not handled (a
// Phong cosine or sample number that small gives 0 either way).
float log2_kernel(float x) {
    int bits = floatBitsToInt(x);
    int e = ((bits >> 23) & 0xff) - 127;
    precise float m = intBitsToFloat((bits & 0x007fffff) | 0x3f800000);  // in [1, 2)
    if (m > 1.41421356f) {
        m = m * 0.5f;
        e += 1;
    }
    precise float t = (m - 1.0f) / (m + 1.0f);
    precise float t2 = t * t;
    precise float series =
        t * (1.0f + t2 * (1.0f / 3.0f + t2 * (1.0f / 5.0f + t2 * (1.0f / 7.0f + t2 * (1.0f / 9.0f + t2 * (1.0f / 11.0f))))));
    precise float result = float(e) + series * 2.88539008f;  // 2 / ln 2
    return result;
}

// 2^z: z = n + f with n the nearest integer, |f| <= 1/2, 2^f = e^(f ln 2) by its
// Taylor series to the 8th power (left out: below 3e-10), scaled by 2^n through the
// exponent bits. Below 2^-126 it is 0 (no denormals), from 2^128 on infinity.
float exp2_kernel(float z) {
    if (!(z >= -126.0f)) {
        return 0.0f;
    }
    if (z >= 128.0f) {
        return uintBitsToFloat(0x7f800000u);
    }
    float n = floor(z + 0.5f);
    precise float r = (z - n) * 0.693147181f;  // ln 2
    precise float p =
        1.0f + r * (1.0f + r * (0.5f + r * (1.0f / 6.0f + r * (1.0f / 24.0f + r * (1.0f / 120.0f +
        r * (1.0f / 720.0f + r * (1.0f / 5040.0f + r * (1.0f / 40320.0f))))))));
    // 2^n in two factors, so that n = 127 (and p < 1) or n = -126 stays representable.
    int half_n = int(n) / 2;
    precise float scaled = p * intBitsToFloat((half_n + 127) << 23) * intBitsToFloat((int(n) - half_n + 127) << 23);
    return scaled;
}

// x^y for x in [0, 1] and y >= 0; x^0 = 1, 0^y = 0 for y > 0.
float power(float x, float y) {
    if (y == 0.0f) {
        return 1.0f;
    }
    if (!(x > 0.0f)) {
        return 0.0f;
    }
    if (x >= 1.0f) {
        return 1.0f;
    }
    return exp2_kernel(y * log2_kernel(x));
}
