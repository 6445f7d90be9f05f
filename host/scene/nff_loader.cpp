// Eric Haines' Neutral File Format (docs/nff.md), the format of the Standard
// Procedural Databases: reads a file into a validated Scene. NFF states one entity
// per line, so every mistake is refused as "<file>:<line>: <what was expected>".
#include "scene/nff_loader.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "scene/cone_mesh.hpp"
#include "scene/json_reader.hpp"  // the JSON loader's magnitude limit and spelling of values
#include "scene/limits.hpp"
#include "scene/polygon.hpp"
#include "scene/read_text.hpp"
#include "scene/scene_error.hpp"
#include "scene/vec_math.hpp"

namespace vkrt {
namespace {

// A vertex count beyond this is a corrupt count, not a polygon.
constexpr std::uint64_t kMaxPolygonVertices = std::uint64_t(1) << 20;

constexpr std::array<std::string_view, 6> kViewKeys{"from", "at", "up", "angle", "hither", "resolution"};
constexpr std::array<std::string_view, 8> kEntityKeys{"v", "b", "l", "f", "s", "p", "pp", "c"};

bool is_keyword(std::string_view word) {
    return std::find(kViewKeys.begin(), kViewKeys.end(), word) != kViewKeys.end() ||
           std::find(kEntityKeys.begin(), kEntityKeys.end(), word) != kEntityKeys.end();
}

// The SPD rule (scenes/spd/README.md): each uncoloured light gets
// sqrt(#lights) / (#lights * 2), so that the lights together stay about as bright
// however many a scene has. It needs the final count, so it is applied at the end.
double spd_light_intensity(std::size_t lights) {
    const double n = static_cast<double>(lights);
    return std::sqrt(n) / (n * 2.0);
}

// A number as C's strtod reads it (which NFF readers have always used): a leading
// '+' is allowed; anything after the number is not. Out-of-range values come back
// as infinity or zero for the caller to judge.
std::optional<double> parse_double(std::string_view s) {
    if (s.size() > 1 && s.front() == '+') s.remove_prefix(1);
    double v = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec == std::errc::invalid_argument || end != s.data() + s.size()) return std::nullopt;
    if (ec == std::errc::result_out_of_range) v = std::strtod(std::string(s).c_str(), nullptr);
    return v;
}

// One line with something on it: its number (from 1) and its whitespace-separated
// fields, the comment ('#' to the end of the line) removed.
struct Line {
    std::size_t number = 0;
    std::vector<std::string_view> fields;
};

// Lines end at "\n", "\r\n" or a lone "\r", so files from any system read alike.
class LineReader {
public:
    explicit LineReader(std::string_view text) : text_(text) {}

    // The next line that holds anything; false at the end of the text.
    bool next(Line& line) {
        while (pos_ < text_.size()) {
            const std::size_t end = std::min(text_.find_first_of("\r\n", pos_), text_.size());
            std::string_view content = text_.substr(pos_, end - pos_);
            const bool crlf = end + 1 < text_.size() && text_[end] == '\r' && text_[end + 1] == '\n';
            pos_ = end + (crlf ? 2 : 1);
            ++number_;
            content = content.substr(0, content.find('#'));
            line.number = number_;
            line.fields.clear();
            for (std::size_t at = content.find_first_not_of(kSpace); at != std::string_view::npos;) {
                const std::size_t stop = std::min(content.find_first_of(kSpace, at), content.size());
                line.fields.push_back(content.substr(at, stop - at));
                at = content.find_first_not_of(kSpace, stop);
            }
            if (!line.fields.empty()) return true;
        }
        return false;
    }

private:
    static constexpr std::string_view kSpace = " \t\v\f";
    std::string_view text_;
    std::size_t pos_ = 0;
    std::size_t number_ = 0;
};

// What the 'f' line in force says. It becomes a Material only when an object uses
// it, and identical ones share one: lattice.nff, for one, has 8,281 'f' lines but
// only 4 different ones, most of them before cylinders.
struct Surface {
    std::array<double, 8> values{};  // r g b Kd Ks Shine T ior, as in the file
    std::size_t line = 0;
    std::optional<std::uint32_t> material;
};

Material to_material(const Surface& s) {
    const auto& [r, g, b, kd, ks, shine, t, ior] = s.values;
    Material m;
    m.name = fmt::format("nff_line_{}", s.line);
    m.diffuse = {r, g, b};
    m.kd = kd;
    // NFF gives the highlight no colour of its own: it is the light reflected off
    // the surface, untinted, like the mirror image that the same Ks weighs.
    m.specular = dvec3(1.0);
    m.ks = ks;
    m.shininess = shine;
    m.reflect = dvec3(ks);
    m.transmit = dvec3(t);
    // The SPD weigh reflection by Ks and refraction by T, whatever the angle.
    m.fresnel = false;
    // The SPD write ior 0 for opaque surfaces; nothing refracts there, so 1 (no
    // bending) stands in and the material stays valid for the refraction to come.
    m.ior = ior > 0.0 ? ior : 1.0;
    return m;
}

class NffReader {
public:
    NffReader(std::string name, std::string_view text) : name_(std::move(name)), lines_(text) {}

    Scene read(const std::filesystem::path& file) {
        scene_.source = file;
        // The SPD test rules (scenes/spd/README.md): rays through the pixel
        // corners, four averaged; a ray tree of depth 5 counting the eye ray, so 4
        // generations after it; every reflection and refraction ray traced, however
        // little it weighs; shadow rays only toward lights in front of the flat
        // surface, as counted. Ambient stays 0: NFF has none.
        scene_.render.aa = 1;
        scene_.render.terminator = false;
        scene_.render.corners = true;
        scene_.render.max_depth = 4;
        scene_.render.min_weight = 0.0;
        for (Line l; lines_.next(l);) read_entity(l);
        if (view_line_ == 0) {
            throw SceneError(fmt::format(
                "{}: no view block (a 'v' line, then from, at, up, angle, hither and resolution lines)", name_));
        }
        finish();
        return std::move(scene_);
    }

private:
    [[noreturn]] void fail(std::size_t line, std::string_view message) const {
        throw SceneError(fmt::format("{}:{}: {}", name_, line, message));
    }

    void read_entity(const Line& l) {
        const std::string_view k = l.fields[0];
        if (k == "v") {
            read_view(l);
        } else if (k == "b") {
            expect_count(l, 3, "r g b");
            scene_.render.background = colour(l, 1, "'b'");
        } else if (k == "l") {
            read_light(l);
        } else if (k == "f") {
            read_surface(l);
        } else if (k == "s") {
            read_sphere(l);
        } else if (k == "p" || k == "pp") {
            read_polygon(l, k == "pp");
        } else if (k == "c") {
            read_cone(l);
        } else if (is_keyword(k)) {
            fail(l.number, fmt::format("'{}' outside a view block (it belongs among the lines after a 'v')", k));
        } else if (parse_double(k)) {
            fail(l.number, "a line of numbers where an entity (v, b, l, f, s, p, pp, c) should start; "
                           "does the polygon above have more vertex lines than its count says?");
        } else {
            fail(l.number, fmt::format("unknown entity {} (expected one of: v, b, l, f, s, p, pp, c)",
                                       json::quote_user(k)));
        }
    }

    // ---- numbers ----------------------------------------------------------------

    // The keyword and exactly `count` fields after it; `syntax` names them.
    void expect_count(const Line& l, std::size_t count, std::string_view syntax) const {
        const std::size_t got = l.fields.size() - 1;
        if (got != count) {
            fail(l.number, fmt::format("expected {} number{} after '{}' ({}), got {}", count, count == 1 ? "" : "s",
                                       l.fields[0], syntax, got));
        }
    }

    double number(const Line& l, std::size_t i, std::string_view label) const {
        const std::string_view token = l.fields[i];
        const std::optional<double> v = parse_double(token);
        if (!v) fail(l.number, fmt::format("{}: expected a number, got {}", label, json::quote_user(token)));
        if (!std::isfinite(*v)) {
            fail(l.number, fmt::format("{}: expected a finite number, got {}", label, json::quote_user(token)));
        }
        if (std::abs(*v) > json::kMaxMagnitude) {
            fail(l.number, fmt::format("{}: expected a number of magnitude at most {}, got {}", label,
                                       json::kMaxMagnitude, token));
        }
        return *v;
    }

    double at_least(const Line& l, std::size_t i, std::string_view label, double lo) const {
        const double v = number(l, i, label);
        if (!(v >= lo)) fail(l.number, fmt::format("{}: expected a number >= {}, got {}", label, lo, l.fields[i]));
        return v;
    }

    std::uint32_t whole(const Line& l, std::size_t i, std::string_view label, std::uint64_t lo,
                        std::uint64_t hi) const {
        const double v = number(l, i, label);
        if (std::floor(v) != v) fail(l.number, fmt::format("{}: expected a whole number, got {}", label, l.fields[i]));
        if (v < static_cast<double>(lo) || v > static_cast<double>(hi)) {
            fail(l.number, fmt::format("{}: expected a whole number in [{}, {}], got {}", label, lo, hi, l.fields[i]));
        }
        return static_cast<std::uint32_t>(v);
    }

    // Three numbers from field `first` on, named "<what> x", "<what> y", ...
    dvec3 vec3(const Line& l, std::size_t first, std::string_view what,
               std::array<std::string_view, 3> names = {"x", "y", "z"}) const {
        dvec3 v;
        for (int k = 0; k < 3; ++k) v[k] = number(l, first + k, fmt::format("{} {}", what, names[k]));
        return v;
    }

    dvec3 colour(const Line& l, std::size_t first, std::string_view what) const {
        dvec3 c;
        constexpr std::array<std::string_view, 3> names{"r", "g", "b"};
        for (int k = 0; k < 3; ++k) c[k] = at_least(l, first + k, fmt::format("{} {}", what, names[k]), 0.0);
        return c;
    }

    // ---- the view -----------------------------------------------------------------

    // The keys of the view block not given yet, as "a, b or c".
    static std::string missing(const std::array<std::size_t, kViewKeys.size()>& at_line, std::string_view last) {
        std::vector<std::string_view> keys;
        for (std::size_t k = 0; k < kViewKeys.size(); ++k) {
            if (at_line[k] == 0) keys.push_back(kViewKeys[k]);
        }
        std::string out;
        for (std::size_t k = 0; k < keys.size(); ++k) {
            if (k > 0) out += k + 1 == keys.size() ? fmt::format(" {} ", last) : std::string(", ");
            out += keys[k];
        }
        return out;
    }

    // 'v' and then its six lines, in any order (the NFF order is from, at, up,
    // angle, hither, resolution; being liberal here costs nothing).
    void read_view(const Line& v) {
        if (view_line_ != 0) fail(v.number, fmt::format("a second view block ('v'); the first is at line {}", view_line_));
        if (v.fields.size() != 1) {
            fail(v.number, fmt::format("expected nothing after 'v' (from, at, up, angle, hither and resolution "
                                       "follow on lines of their own), got {}",
                                       json::quote_user(v.fields[1])));
        }
        view_line_ = v.number;
        std::array<std::size_t, kViewKeys.size()> at_line{};  // where each key was given; 0: not yet
        Camera& c = scene_.camera;
        for (std::size_t n = 0; n < kViewKeys.size(); ++n) {
            Line l;
            if (!lines_.next(l)) {
                fail(v.number, fmt::format("the file ends inside this view block, which lacks {}", missing(at_line, "and")));
            }
            const std::string_view k = l.fields[0];
            const auto key = std::find(kViewKeys.begin(), kViewKeys.end(), k);
            if (key == kViewKeys.end()) {
                fail(l.number, fmt::format("expected {} in the view block that starts at line {}, got {}",
                                           missing(at_line, "or"), v.number, json::quote_user(k)));
            }
            std::size_t& seen = at_line[static_cast<std::size_t>(key - kViewKeys.begin())];
            if (seen != 0) fail(l.number, fmt::format("'{}' given twice in the view block (first at line {})", k, seen));
            seen = l.number;
            if (k == "from" || k == "at" || k == "up") {
                expect_count(l, 3, "x y z");
                (k == "from" ? c.eye : k == "at" ? c.look_at : c.up) = vec3(l, 1, fmt::format("'{}'", k));
            } else if (k == "angle") {
                expect_count(l, 1, "the vertical field of view in degrees");
                c.fov = number(l, 1, "'angle'");
                if (!(c.fov > 0.0 && c.fov < 180.0)) {
                    fail(l.number, fmt::format("'angle': expected a number strictly between 0 and 180, got {}",
                                               l.fields[1]));
                }
            } else if (k == "hither") {
                // Read for its errors, then ignored: it is the near clipping plane of
                // scan-line and z-buffer renderers ("mostly needed for hidden
                // surface algorithms", says the NFF description). Eye rays start at
                // the eye, and no SPD scene puts anything that near it.
                expect_count(l, 1, "the distance of the near clipping plane");
                number(l, 1, "'hither'");
            } else {
                expect_count(l, 2, "width height");
                c.width = whole(l, 1, "'resolution' width", 1, limits::kMaxImageSide);
                c.height = whole(l, 2, "'resolution' height", 1, limits::kMaxImageSide);
                // NFF scenes render by the SPD corner rule (read() below).
                if (const std::string problem = limits::image_size_problem(c.width, c.height, true);
                    !problem.empty()) {
                    fail(l.number, problem);
                }
            }
        }
        const dvec3 view = c.look_at - c.eye;
        if (!is_nonzero(view)) {
            fail(at_line[1], fmt::format("'at' must differ from 'from' (both are {})", json::format_vec3(c.eye)));
        }
        if (!is_nonzero(c.up)) fail(at_line[2], "'up': expected a non-zero vector, got [0, 0, 0]");
        if (parallel_or_zero(c.up, view, kParallelSine)) {
            fail(at_line[2], fmt::format("'up' {} is parallel to the view direction at - from = {}",
                                         json::format_vec3(c.up), json::format_vec3(view)));
        }
    }

    // ---- lights and surfaces ------------------------------------------------------

    void read_light(const Line& l) {
        const std::size_t got = l.fields.size() - 1;
        if (got != 3 && got != 6) {
            fail(l.number, fmt::format("expected 3 or 6 numbers after 'l' (x y z [r g b]), got {}", got));
        }
        Light light;
        light.position = vec3(l, 1, "'l'");
        // A coloured light's colour is its brightness: it is used as given, while
        // the uncoloured ones get the SPD intensity in finish().
        if (got == 6) light.color = colour(l, 4, "'l'");
        scene_.lights.push_back(light);
        coloured_.push_back(got == 6);
    }

    void read_surface(const Line& l) {
        expect_count(l, 8, "r g b Kd Ks Shine T ior");
        constexpr std::array<std::string_view, 8> names{"r", "g", "b", "Kd", "Ks", "Shine", "T", "ior"};
        Surface s;
        s.line = l.number;
        for (std::size_t k = 0; k < names.size(); ++k) s.values[k] = at_least(l, k + 1, fmt::format("'f' {}", names[k]), 0.0);
        if (s.values[6] > 0.0 && !(s.values[7] > 0.0)) {
            fail(l.number, fmt::format("'f' ior: expected a number > 0 for a transmitting surface (T = {}), got {}",
                                       l.fields[7], l.fields[8]));
        }
        surface_ = s;
    }

    // The material of the 'f' in force, made (or found) the first time an object uses it.
    std::uint32_t material_for(const Line& l) {
        if (!surface_) {
            fail(l.number, fmt::format("'{}' comes before any 'f' line, so it has no material (an 'f' line sets "
                                       "the material of the objects after it)",
                                       l.fields[0]));
        }
        if (!surface_->material) {
            const auto [it, added] =
                materials_.try_emplace(surface_->values, static_cast<std::uint32_t>(scene_.materials.size()));
            if (added) scene_.materials.push_back(to_material(*surface_));
            surface_->material = it->second;
        }
        return *surface_->material;
    }

    // ---- objects --------------------------------------------------------------------

    void read_sphere(const Line& l) {
        expect_count(l, 4, "x y z radius");
        Sphere s;
        s.center = vec3(l, 1, "'s'");
        s.radius = number(l, 4, "'s' radius");
        if (!(s.radius > 0.0)) fail(l.number, fmt::format("'s' radius: expected a number > 0, got {}", l.fields[4]));
        s.material = material_for(l);
        scene_.spheres.push_back(s);
    }

    // 'p n' or 'pp n', then n vertex lines: split into triangles that keep the
    // polygon's winding. NFF polygons turn counter-clockwise seen from the front;
    // the renderer shades both sides alike (it turns normals toward the ray), so
    // which side is the front matters only for emission, which NFF has not.
    void read_polygon(const Line& l, bool with_normals) {
        const std::string_view k = l.fields[0];
        expect_count(l, 1, "the vertex count");
        const std::uint32_t count = whole(l, 1, fmt::format("'{}' vertex count", k), 3, kMaxPolygonVertices);
        const std::uint32_t material = material_for(l);
        const std::size_t per_vertex = with_normals ? 6 : 3;
        std::vector<dvec3> vertices;
        std::vector<dvec3> normals;
        for (std::uint32_t i = 0; i < count; ++i) {
            Line vl;
            if (!lines_.next(vl)) {
                fail(l.number, fmt::format("the file ends after {} of the {} vertex lines of this '{}'", i, count, k));
            }
            if (is_keyword(vl.fields[0])) {
                fail(vl.number, fmt::format("expected vertex {} of {} of the '{}' at line {}, got a '{}' line "
                                            "(is the vertex count right?)",
                                            i + 1, count, k, l.number, vl.fields[0]));
            }
            if (vl.fields.size() != per_vertex) {
                fail(vl.number, fmt::format("expected {} numbers on vertex line {} of the '{}' at line {} ({}), got {}",
                                            per_vertex, i + 1, k, l.number, with_normals ? "x y z nx ny nz" : "x y z",
                                            vl.fields.size()));
            }
            const std::string what = fmt::format("'{}' vertex {}", k, i + 1);
            vertices.push_back(vec3(vl, 0, what));
            if (with_normals) {
                const dvec3 n = vec3(vl, 3, what, {"nx", "ny", "nz"});
                if (!is_nonzero(n)) fail(vl.number, fmt::format("{} normal: expected a non-zero vector, got [0, 0, 0]", what));
                // Normalized here so the kernel can interpolate without renormalizing inputs.
                normals.push_back(robust_normalize(n));
            }
        }
        if (count > kMaxConcavePolygonVertices && !polygon_is_convex(vertices)) {
            fail(l.number, fmt::format("a non-convex polygon of {} vertices; vkrt splits non-convex polygons of at "
                                       "most {} vertices into triangles",
                                       count, kMaxConcavePolygonVertices));
        }
        const PolygonTriangles split = triangulate_polygon(vertices);
        for (const auto& [a, b, c] : split.triangles) {
            Triangle t{{vertices[a], vertices[b], vertices[c]}, std::nullopt, material};
            if (with_normals) t.normals = std::array{normals[a], normals[b], normals[c]};
            scene_.triangles.push_back(t);
        }
        if (split.degenerate > 0) {
            if (degenerate_triangles_ == 0) first_degenerate_line_ = l.number;
            degenerate_triangles_ += split.degenerate;
            ++degenerate_polygons_;
        }
        if (!split.simple) {
            if (crossed_polygons_ == 0) first_crossed_line_ = l.number;
            ++crossed_polygons_;
        }
    }

    // 'c': a cone or cylinder between two points, open at both ends. The SPD files
    // write all 8 numbers on the 'c' line (base x y z r0 apex x y z r1); the README
    // gives 'c' alone, then two lines "x y z r": both are NFF. Equal radii make an
    // open cylinder (exact in the kernel); different ones a cone of triangles
    // (host/scene/cone_mesh.hpp).
    void read_cone(const Line& l) {
        std::array<Line, 2> ends;
        std::array<std::size_t, 2> first{};  // where each end's numbers start in its line
        if (l.fields.size() == 9) {
            ends = {l, l};
            first = {1, 5};
        } else if (l.fields.size() == 1) {
            for (std::size_t e = 0; e < 2; ++e) {
                if (!lines_.next(ends[e])) {
                    fail(l.number, fmt::format("the file ends after {} of the 2 lines (x y z radius) of this 'c'", e));
                }
                if (is_keyword(ends[e].fields[0])) {
                    fail(ends[e].number, fmt::format("expected line {} of 2 (x y z radius) of the 'c' at line {}, got "
                                                     "a '{}' line",
                                                     e + 1, l.number, ends[e].fields[0]));
                }
                if (ends[e].fields.size() != 4) {
                    fail(ends[e].number, fmt::format("expected 4 numbers on line {} of 2 of the 'c' at line {} "
                                                     "(x y z radius), got {}",
                                                     e + 1, l.number, ends[e].fields.size()));
                }
            }
        } else {
            fail(l.number, fmt::format("expected 8 numbers after 'c' (base x y z r0 apex x y z r1), or none and "
                                       "then two lines x y z r, got {}",
                                       l.fields.size() - 1));
        }
        constexpr std::array<std::string_view, 2> names{"base", "apex"};
        std::array<dvec3, 2> centre;
        std::array<double, 2> radius{};
        for (std::size_t e = 0; e < 2; ++e) {
            const std::string what = fmt::format("'c' {}", names[e]);
            centre[e] = vec3(ends[e], first[e], what);
            radius[e] = at_least(ends[e], first[e] + 3, what + " radius", 0.0);
        }
        if (radius[0] == 0.0 && radius[1] == 0.0) {
            fail(l.number, "'c': the base and apex radii are both 0, so it has no surface");
        }
        if (glm::vec3(centre[0]) == glm::vec3(centre[1])) {
            fail(l.number, fmt::format("'c': the base {} and apex {} are the same point (in single precision), so it "
                                       "has no axis",
                                       json::format_vec3(centre[0]), json::format_vec3(centre[1])));
        }
        const std::uint32_t material = material_for(l);
        if (radius[0] == radius[1]) {
            scene_.cylinders.push_back(Cylinder{centre[0], centre[1], radius[0], false, material});
        } else {
            // Sides enough for the file's own view; a 'c' before the view block (NFF
            // puts the view first) gets the most.
            const std::uint32_t segments =
                view_line_ != 0 ? cone_segments(centre[0], radius[0], centre[1], radius[1], scene_.camera)
                                : kMaxConeSegments;
            const std::vector<Triangle> cone =
                tessellate_cone(centre[0], radius[0], centre[1], radius[1], material, segments);
            scene_.triangles.insert(scene_.triangles.end(), cone.begin(), cone.end());
        }
    }

    // ---- after the last line ------------------------------------------------------

    void finish() {
        const std::size_t n = scene_.lights.size();
        for (std::size_t i = 0; i < n; ++i) {
            if (!coloured_[i]) scene_.lights[i].intensity = spd_light_intensity(n);
        }
        auto& warnings = scene_.warnings;
        const auto many = [](std::size_t count, std::string_view one, std::string_view more) {
            return fmt::format("{} {}", count, count == 1 ? one : more);
        };
        if (degenerate_triangles_ > 0) {
            warnings.push_back(fmt::format("{}: left out {} of {} (the first at line {}); they cover nothing",
                                           name_, many(degenerate_triangles_, "zero-area triangle", "zero-area triangles"),
                                           many(degenerate_polygons_, "polygon", "polygons"), first_degenerate_line_));
        }
        if (crossed_polygons_ > 0) {
            warnings.push_back(fmt::format("{}: {} (the first at line {}); split as a fan from the first vertex, "
                                           "they may look wrong",
                                           name_, many(crossed_polygons_, "polygon crosses itself", "polygons cross themselves"),
                                           first_crossed_line_));
        }
    }

    std::string name_;
    LineReader lines_;
    Scene scene_;
    std::size_t view_line_ = 0;
    std::vector<bool> coloured_;  // per light: given with a colour
    std::optional<Surface> surface_;
    std::map<std::array<double, 8>, std::uint32_t> materials_;  // 'f' values -> material index
    std::size_t degenerate_triangles_ = 0;
    std::size_t degenerate_polygons_ = 0;
    std::size_t first_degenerate_line_ = 0;
    std::size_t crossed_polygons_ = 0;
    std::size_t first_crossed_line_ = 0;
};

}  // namespace

Scene load_nff_scene(const std::filesystem::path& file) {
    const std::string name = file.string();
    const std::string text = read_text(file, name, "scene");
    return NffReader(name, text).read(file);
}

}  // namespace vkrt
