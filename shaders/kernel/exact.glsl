// Error-free transformations: a product or a sum as its rounded value and the
// rounding error, exactly (the sphere's error-free test builds on them).

// a * b as hi + lo exactly: hi the rounded product, lo its rounding error (Dekker's
// product, splitting each factor into two 12-bit halves as Veltkamp does, so that the
// four partial products are exact without a fused multiply-add). `precise` keeps a
// compiler from simplifying (c - (c - a)) to a. 4097 * a must not overflow (|a| < 8e34).
vec2 exact_product(float a, float b) {
    const float SPLIT = 4097.0f;  // 2^12 + 1
    precise float ca = SPLIT * a;
    precise float a_hi = ca - (ca - a);
    precise float a_lo = a - a_hi;
    precise float cb = SPLIT * b;
    precise float b_hi = cb - (cb - b);
    precise float b_lo = b - b_hi;
    precise float hi = a * b;
    precise float lo = ((a_hi * b_hi - hi) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo;
    return vec2(hi, lo);
}

// a + b as hi + lo exactly (Knuth's two-sum).
vec2 exact_sum(float a, float b) {
    precise float s = a + b;
    precise float b_virtual = s - a;
    precise float lo = (a - (s - b_virtual)) + (b - b_virtual);
    return vec2(s, lo);
}
