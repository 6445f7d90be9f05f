// Exact per-pixel sums. Any split of a pixel's samples (over passes, runs or
// machines) must add up to the very image of one run (docs/architecture.md,
// principle 4). Float addition is
// not associative: (s0 + s1) + (s2 + s3 + s4) is not ((((s0 + s1) + s2) + s3) + s4),
// so float sums could only promise that up to a rounding. Here each sample's
// radiance is instead rounded down once to a multiple of 2^-40 (a fixed step, the
// same on both backends) and added as a 96-bit integer, three 32-bit words with
// carries. Integer addition is associative: partial sums added in any order are the
// whole run's sum bit for bit, and nothing drifts at high sample counts either.
//
// Range: a channel of one sample is clamped to [0, SUM_SAMPLE_MAX], the largest float
// below 2^40 (about 1.1e12); 65,536 samples (the most a pixel takes) of that sum to
// less than 2^96. The squares are summed alike (add_sample), for the variance of the
// mean (host/render/pixel_sums.hpp): a square beyond SUM_SAMPLE_MAX (a radiance
// beyond about 1e6) is clamped, which only an image of such radiance would notice. The step 2^-40 (about 9.1e-13) is far below anything an image
// shows at the radiance of a scene; a radiance smaller than that is summed as 0.
// Samples that had to be clamped are counted (PixelSum.green.w).
//
// Included at namespace scope by host/kernel/types.hpp and by shaders/render.comp,
// so that the host merges partial sums with the very functions the kernel adds with.
// There they live in a header, so C++ defines HOST_INLINE as `inline`.
#ifndef HOST_INLINE
#define HOST_INLINE
#endif

const float SUM_SAMPLE_MAX = 1099511562240.0f;  // 2^40 - 2^16
const float SUM_SCALE = 1099511627776.0f;        // 2^40: one unit of the sum is 2^-40
const float TWO_POW_32 = 4294967296.0f;
const float TWO_POW_64 = 18446744073709551616.0f;

// x * 2^40 (x in [0, SUM_SAMPLE_MAX]) as a 96-bit integer, least significant word
// first, its fraction dropped. Every step is exact in float: the products scale by
// powers of two, floor() cuts bits off, and each difference is a subset of the bits
// of a float that is already there, so both backends get the same words.
HOST_INLINE uvec3 fixed_point(float x) {
    float v = x * SUM_SCALE;                      // < 2^80
    float hi = floor(v * (1.0f / TWO_POW_64));    // < 2^16
    float rest = v - hi * TWO_POW_64;             // < 2^64
    float mid = floor(rest * (1.0f / TWO_POW_32));
    float lo = rest - mid * TWO_POW_32;           // < 2^32, fraction truncated by uint()
    return uvec3(uint(lo), uint(mid), uint(hi));
}

// a + b in 96 bits (the words of a sum never overflow the top: see the range above).
HOST_INLINE uvec3 add_words(uvec3 a, uvec3 b) {
    uint lo = a.x + b.x;
    uint carry_lo = lo < a.x ? 1u : 0u;
    uint mid = a.y + b.y;
    uint carry_mid = mid < a.y ? 1u : 0u;
    uint mid_carried = mid + carry_lo;
    carry_mid += mid_carried < mid ? 1u : 0u;
    return uvec3(lo, mid_carried, a.z + b.z + carry_mid);
}

// Adds one sample's radiance (finite; the caller has checked) to a pixel's sums, and
// where `squares` (HAS_SQUARES) its square to the squares' sums: the float square of
// the clamped channel (one correctly rounded product on either backend), itself
// clamped to SUM_SAMPLE_MAX, so that squares add as exactly as the radiance does.
HOST_INLINE void add_sample(INOUT(PixelSum) sum, vec3 radiance, bool squares) {
    bool clamped = any(greaterThan(radiance, vec3(SUM_SAMPLE_MAX)));
    vec3 r = clamp(radiance, vec3(0.0f), vec3(SUM_SAMPLE_MAX));
    precise vec3 squared = r * r;
    vec3 q = min(squared, vec3(SUM_SAMPLE_MAX));
    sum.red = uvec4(add_words(uvec3(sum.red), fixed_point(r.x)), sum.red.w + 1u);
    sum.green = uvec4(add_words(uvec3(sum.green), fixed_point(r.y)), sum.green.w + (clamped ? 1u : 0u));
    sum.blue = uvec4(add_words(uvec3(sum.blue), fixed_point(r.z)), sum.blue.w);
    if (squares) {
        sum.red_squares = uvec4(add_words(uvec3(sum.red_squares), fixed_point(q.x)), 0u);
        sum.green_squares = uvec4(add_words(uvec3(sum.green_squares), fixed_point(q.y)), 0u);
        sum.blue_squares = uvec4(add_words(uvec3(sum.blue_squares), fixed_point(q.z)), 0u);
    }
}

// The sums of two disjoint sets of samples of one pixel: those of their union.
HOST_INLINE PixelSum add_sums(PixelSum a, PixelSum b) {
    return PixelSum(uvec4(add_words(uvec3(a.red), uvec3(b.red)), a.red.w + b.red.w),
                    uvec4(add_words(uvec3(a.green), uvec3(b.green)), a.green.w + b.green.w),
                    uvec4(add_words(uvec3(a.blue), uvec3(b.blue)), a.blue.w + b.blue.w),
                    uvec4(add_words(uvec3(a.red_squares), uvec3(b.red_squares)), 0u),
                    uvec4(add_words(uvec3(a.green_squares), uvec3(b.green_squares)), 0u),
                    uvec4(add_words(uvec3(a.blue_squares), uvec3(b.blue_squares)), 0u));
}

// Adds the eye ray's hit to a pixel's render passes (layout.glsl's PassSums): each
// channel of the base colour, of the shading normal plus one and of the distance,
// clamped to [0, SUM_SAMPLE_MAX], summed exactly as radiance is.
HOST_INLINE void add_first_hit(INOUT(PassSums) p, vec3 albedo, vec3 normal, float depth) {
    vec3 a = clamp(albedo, vec3(0.0f), vec3(SUM_SAMPLE_MAX));
    vec3 n = clamp(normal + vec3(1.0f), vec3(0.0f), vec3(2.0f));
    float d = clamp(depth, 0.0f, SUM_SAMPLE_MAX);
    p.albedo_red = uvec4(add_words(uvec3(p.albedo_red), fixed_point(a.x)), 0u);
    p.albedo_green = uvec4(add_words(uvec3(p.albedo_green), fixed_point(a.y)), 0u);
    p.albedo_blue = uvec4(add_words(uvec3(p.albedo_blue), fixed_point(a.z)), 0u);
    p.normal_x = uvec4(add_words(uvec3(p.normal_x), fixed_point(n.x)), 0u);
    p.normal_y = uvec4(add_words(uvec3(p.normal_y), fixed_point(n.y)), 0u);
    p.normal_z = uvec4(add_words(uvec3(p.normal_z), fixed_point(n.z)), 0u);
    p.depth = uvec4(add_words(uvec3(p.depth), fixed_point(d)), 0u);
}

// The render passes of two disjoint sets of samples of one pixel: those of their union.
HOST_INLINE PassSums add_pass_sums(PassSums a, PassSums b) {
    return PassSums(uvec4(add_words(uvec3(a.albedo_red), uvec3(b.albedo_red)), 0u),
                    uvec4(add_words(uvec3(a.albedo_green), uvec3(b.albedo_green)), 0u),
                    uvec4(add_words(uvec3(a.albedo_blue), uvec3(b.albedo_blue)), 0u),
                    uvec4(add_words(uvec3(a.normal_x), uvec3(b.normal_x)), 0u),
                    uvec4(add_words(uvec3(a.normal_y), uvec3(b.normal_y)), 0u),
                    uvec4(add_words(uvec3(a.normal_z), uvec3(b.normal_z)), 0u),
                    uvec4(add_words(uvec3(a.depth), uvec3(b.depth)), 0u));
}
