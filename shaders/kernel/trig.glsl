// The kernel's own sine, cosine and arc tangent, from additions, multiplications,
// divisions and square roots only, each rounded once (precise: no fused
// multiply-add). Those are correctly rounded on every Vulkan device and in C++, so
// both backends get the same bits; the built-in sin, cos and atan are not: Vulkan
// allows them an absolute error of 2^-11 (sin, cos) and 4096 ULP (atan), lavapipe
// and the C library differ in their last bits (docs/numerics.md), and a light
// sampled by solid angle passes those bits on to the image in every pixel.

// pi / 2 split in two: the first with its low bits zero, so that n times it is exact
// for the few quadrants n the kernel's angles (in [-8, 8]) reach; the second the rest.
const float HALF_PI_HIGH = 1.57079601287841796875f;
const float HALF_PI_LOW = 3.1391647865e-7f;

// (sin x, cos x) for x in [-8, 8]: x less the nearest multiple n of pi/2 (Cody and
// Waite's reduction), whose sine and cosine are their Taylor series on [-pi/4, pi/4]
// (the first omitted terms are below 3e-9), then swapped and negated by quadrant.
vec2 sin_cos(float x) {
    float n = floor(x * (2.0f / PI) + 0.5f);
    precise float r = (x - n * HALF_PI_HIGH) - n * HALF_PI_LOW;
    precise float r2 = r * r;
    precise float s = r + r * r2 * (-1.0f / 6.0f + r2 * (1.0f / 120.0f + r2 * (-1.0f / 5040.0f + r2 * (1.0f / 362880.0f))));
    precise float c = 1.0f + r2 * (-0.5f + r2 * (1.0f / 24.0f + r2 * (-1.0f / 720.0f +
                      r2 * (1.0f / 40320.0f + r2 * (-1.0f / 3628800.0f)))));
    int quadrant = int(n) & 3;
    if (quadrant == 0) {
        return vec2(s, c);
    }
    if (quadrant == 1) {
        return vec2(c, -s);
    }
    if (quadrant == 2) {
        return vec2(-s, -c);
    }
    return vec2(-c, s);
}

// atan(t) for t in [0, 1]: the half-angle identity atan(t) = 2 atan(t / (1 +
// sqrt(1 + t^2))) twice brings t below tan(pi/16) = 0.199, where seven terms of the
// series t - t^3/3 + t^5/5 - ... leave out less than 3e-12.
float atan_unit(float t) {
    precise float h1 = t / (1.0f + sqrt(1.0f + t * t));
    precise float h2 = h1 / (1.0f + sqrt(1.0f + h1 * h1));
    precise float q = h2 * h2;
    precise float a = h2 * (1.0f + q * (-1.0f / 3.0f + q * (1.0f / 5.0f + q * (-1.0f / 7.0f + q * (1.0f / 9.0f +
                      q * (-1.0f / 11.0f + q * (1.0f / 13.0f)))))));
    return 4.0f * a;
}

// The angle of the point (x, y) with y >= 0, in [0, pi]: atan(y, x) on the upper
// half-plane.
float upper_half_plane_angle(float y, float x) {
    float ax = abs(x);
    precise float a = ax >= y ? atan_unit(y / ax) : 0.5f * PI - atan_unit(ax / y);
    return x >= 0.0f ? a : PI - a;
}
