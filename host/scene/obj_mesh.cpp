// OBJ files are read in one pass over the text: every line that carries geometry is
// checked and its numbers taken, so that a malformed number ("nan", "1,5", "abc") is
// refused with its line instead of silently changing the model's shape. Faces are
// kept as polygons of corners (v, v/vt, v/vt/vn, v//vn, negative indices counting
// back from the last element read) and triangulated as fans once the whole file is
// read, when every index can be checked. MTL files are read by tinyobjloader (its
// texture options), after their numbers are checked as the OBJ's are.
#include "scene/obj_mesh.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include "scene/read_text.hpp"
#include "scene/scene_error.hpp"
#include "scene/texture_image.hpp"
#include "scene/vec_math.hpp"

namespace vkrt {
namespace {

using glm::dvec3;

// At most this many vertices per face: tinyobjloader, which read faces before, kept
// the count in an unsigned char, and files with more were refused then.
constexpr std::size_t kMaxFaceVertices = 255;

// The words of one OBJ or MTL line, into `words`; a comment runs from '#' to the end
// of the line.
void split_words(std::string_view line, std::vector<std::string_view>& words) {
    words.clear();
    line = line.substr(0, line.find('#'));
    std::size_t at = 0;
    while (true) {
        at = line.find_first_not_of(" \t\r", at);
        if (at == std::string_view::npos) break;
        const std::size_t end = std::min(line.find_first_of(" \t\r", at), line.size());
        words.push_back(line.substr(at, end - at));
        at = end;
    }
}

// Calls statement(line number from 1, words) for every line of the text with words.
template <class F>
void for_each_statement(std::string_view text, F&& statement) {
    std::vector<std::string_view> words;  // one buffer for every line
    std::size_t start = 0, line = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        ++line;
        split_words(text.substr(start, end - start), words);
        if (!words.empty()) statement(line, words);
        start = end + 1;
    }
}

// A number of an OBJ or MTL file, or an error naming FILE:LINE: finite, and at most
// json::kMaxMagnitude in magnitude, as the scene's own numbers.
double file_number(std::string_view word, const std::string& name, std::size_t line) {
    const auto fail = [&](const std::string& message) {
        throw SceneError(fmt::format("{}:{}: {}", name, line, message));
    };
    std::string_view digits = word;
    if (digits.size() > 1 && digits[0] == '+') digits.remove_prefix(1);  // from_chars takes no '+'
    double x = 0.0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), x);
    if (end != digits.data() + digits.size() || ec == std::errc::invalid_argument) {
        fail(fmt::format("expected a number, got {}", json::quote_user(word)));
    }
    if (ec == std::errc::result_out_of_range) {
        // Either too large for a double or too small: strtod says which.
        x = std::strtod(std::string(digits).c_str(), nullptr);
    }
    if (!std::isfinite(x)) fail(fmt::format("expected a finite number, got {}", json::quote_user(word)));
    if (std::abs(x) > json::kMaxMagnitude) {
        fail(fmt::format("expected a number of magnitude at most {}, got {}", json::kMaxMagnitude,
                         json::quote_user(word)));
    }
    return x;
}

// The numbers of an MTL file's colour, exponent and dissolve lines, checked as
// the OBJ's are (tinyobjloader reads "abc" or "0,8" as 0 and a missing colour
// component as 0): a typo is refused with its line instead of rendering black.
void check_mtl(const std::filesystem::path& file) {
    const std::string name = file.string();
    const std::string text = read_text(file, name, "material");
    for_each_statement(text, [&](std::size_t line, const std::vector<std::string_view>& words) {
        const std::string_view keyword = words[0];
        const bool colour = keyword == "Kd" || keyword == "Ks" || keyword == "Ke" || keyword == "Ka" || keyword == "Tf";
        if (!colour && keyword != "Ns" && keyword != "d" && keyword != "Tr") return;
        const std::size_t wanted = colour ? 3 : 1;
        if (words.size() - 1 != wanted) {
            throw SceneError(fmt::format("{}:{}: expected {} number{} after '{}', got {}", name, line, wanted,
                                         wanted == 1 ? "" : "s", keyword, words.size() - 1));
        }
        for (std::size_t i = 1; i < words.size(); ++i) file_number(words[i], name, line);
    });
}

// An MTL material as vkrt's Phong material: Kd the diffuse colour, Ks the
// specular one (ks 1 when it is not black), Ns the exponent, Ke the emission.
// What vkrt cannot show yet is said once per material and feature.
Material from_mtl(const tinyobj::material_t& m, const std::string& obj_name, std::vector<std::string>& warnings) {
    const std::string who = fmt::format("{}: material {}", obj_name, json::quote_user(m.name));
    const auto colour = [&](const tinyobj::real_t* c, const char* keyword) {
        const dvec3 v(c[0], c[1], c[2]);
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || v.x < 0 || v.y < 0 || v.z < 0) {
            throw SceneError(fmt::format("{}: {} must be three finite numbers >= 0, got {}", who, keyword,
                                         json::format_vec3(v)));
        }
        return v;
    };
    Material out;
    out.name = m.name;
    out.diffuse = colour(m.diffuse, "Kd");
    out.specular = colour(m.specular, "Ks");
    out.ks = is_nonzero(out.specular) ? 1.0 : 0.0;
    out.emission = colour(m.emission, "Ke");
    if (!std::isfinite(m.shininess) || m.shininess < 0) {
        throw SceneError(fmt::format("{}: Ns must be a finite number >= 0, got {}", who, m.shininess));
    }
    out.shininess = m.shininess;
    // map_Kd is read by read_mesh (it needs the scene); with tinyobjloader's -o and
    // -s options as the coordinates' transform, the v axis turned to run down as
    // vkrt's textures do (read_obj flips the file's v): v' = s v + 1 - s - o.
    if (!m.diffuse_texname.empty()) {
        const tinyobj::texture_option_t& o = m.diffuse_texopt;
        out.uv_transform = {o.scale[0], 0.0, o.origin_offset[0], 0.0, o.scale[1], 1.0 - o.scale[1] - o.origin_offset[1]};
    }
    const std::pair<const char*, const std::string*> maps[] = {
        {"map_Ks", &m.specular_texname}, {"map_Ns", &m.specular_highlight_texname},
        {"map_bump", &m.bump_texname},   {"map_Ka", &m.ambient_texname},  {"map_d", &m.alpha_texname},
        {"disp", &m.displacement_texname}, {"refl", &m.reflection_texname}, {"map_Ke", &m.emissive_texname},
        {"norm", &m.normal_texname}};
    for (const auto& [keyword, texture] : maps) {
        if (!texture->empty()) {
            warnings.push_back(fmt::format("{}: textures are not supported yet; {} {} is ignored", who, keyword,
                                           json::quote_user(*texture)));
        }
    }
    if (m.dissolve < 1) {
        warnings.push_back(fmt::format("{}: transparency (d {}) is not supported; the material is opaque", who,
                                       m.dissolve));
    }
    return out;
}

// The MTL files an OBJ names, read as tinyobjloader reads them while it reads an OBJ:
// of each mtllib line's files, the first that was not read before and can be opened,
// relative to the OBJ's directory. A usemtl finds its material among those read so
// far; where two have one name, the first read.
class MaterialLibraries {
public:
    explicit MaterialLibraries(const std::filesystem::path& obj)
        : dir_(obj.parent_path().empty() ? std::filesystem::path(".") : obj.parent_path()),
          // The directory with its separator ("box.obj" alone is in "./", not "/").
          reader_(dir_.string() + "/") {}

    // One mtllib line's files. Every one of them that is there has its numbers
    // checked first (check_mtl).
    void add(std::span<const std::string_view> files) {
        for (const std::string_view file : files) {
            names_.emplace_back(file);
            if (std::filesystem::is_regular_file(dir_ / names_.back())) {
                check_mtl(dir_ / names_.back());
            } else {
                unreadable_.push_back(names_.back());
            }
        }
        for (const std::string_view file : files) {
            const std::string name(file);
            if (read_.contains(name)) continue;
            // tinyobjloader's warnings say less than the checks above and the
            // errors of the faces left without a material.
            std::string warning, error;
            if (reader_(name, &materials_, &by_name_, &warning, &error)) {
                read_.insert(name);
                break;
            }
        }
    }

    // The index of the material called `name` among those read so far, or -1.
    int find(const std::string& name) const {
        const auto found = by_name_.find(name);
        return found == by_name_.end() ? -1 : found->second;
    }

    const std::vector<std::string>& names() const { return names_; }            // every file named
    const std::vector<std::string>& unreadable() const { return unreadable_; }  // those not there
    const std::vector<tinyobj::material_t>& materials() const { return materials_; }

private:
    std::filesystem::path dir_;
    tinyobj::MaterialFileReader reader_;
    std::vector<std::string> names_;
    std::vector<std::string> unreadable_;
    std::set<std::string> read_;
    std::vector<tinyobj::material_t> materials_;
    std::map<std::string, int> by_name_;
};

// One corner of a face: indices from 0 into the file's positions, texture
// coordinates and normals, as the file gives them (checked against the counts only
// once the whole file is read: an index may refer to a later line).
struct Corner {
    static constexpr std::int64_t kNone = std::numeric_limits<std::int64_t>::min();
    std::int64_t position = kNone;
    std::int64_t uv = kNone;
    std::int64_t normal = kNone;
};

// One face of the file, a polygon: corners [first, first + count).
struct Polygon {
    std::size_t first = 0;
    std::size_t count = 0;
    std::size_t line = 0;
    int material = -1;       // into the libraries' materials; -1: its usemtl found none
    std::size_t usemtl = 0;  // into ParsedObj::usemtl_names: what its usemtl asked for
};

// What one pass over an OBJ file takes from it.
struct ParsedObj {
    std::vector<dvec3> positions;
    // Per position, its colour ("v x y z r g b", sRGB-decoded), white where the line
    // has none; used when any line has one.
    std::vector<glm::vec4> colors;
    bool any_color = false;
    std::vector<dvec3> normals;
    std::vector<glm::dvec2> uvs;  // v turned to run down the image, as vkrt's textures do
    std::vector<Corner> corners;  // every face's, in file order
    std::vector<Polygon> polygons;
    std::vector<std::string> usemtl_names{""};  // [0]: no usemtl yet
};

// Reads an OBJ file's lines, refusing a malformed one with its line. `libraries`,
// when the file's materials are wanted, reads the files mtllib lines name; without
// it mtllib lines are skipped rather than opened (the scene gives the material).
class ObjParser {
public:
    ObjParser(const std::string& name, MaterialLibraries* libraries) : name_(name), libraries_(libraries) {}

    ParsedObj parse(std::string_view text) {
        for_each_statement(text, [this](std::size_t line, const std::vector<std::string_view>& words) {
            line_ = line;
            statement(words);
        });
        return std::move(out_);
    }

private:
    [[noreturn]] void fail(std::string_view message) const {
        throw SceneError(fmt::format("{}:{}: {}", name_, line_, message));
    }

    void statement(const std::vector<std::string_view>& words) {
        const std::string_view keyword = words[0];
        if (keyword == "v") {
            out_.positions.push_back(triple(words, "v"));
            out_.colors.push_back(vertex_color(words));
        } else if (keyword == "vn") {
            out_.normals.push_back(triple(words, "vn"));
        } else if (keyword == "vt") {
            out_.uvs.push_back(texture_coordinate(words));
        } else if (keyword == "f") {
            face(words);
        } else if (keyword == "usemtl") {
            use_material(words.size() > 1 ? std::string(words[1]) : std::string());
        } else if (keyword == "mtllib" && libraries_ != nullptr) {
            libraries_->add(std::span(words).subspan(1));
        }
        // Every other statement (g, o, s, l, p, ...) carries nothing vkrt uses.
    }

    // The first three numbers of a "v" or "vn" line; the rest (w, vertex colours)
    // must be numbers too.
    dvec3 triple(const std::vector<std::string_view>& words, std::string_view keyword) const {
        if (words.size() < 4) {
            fail(fmt::format("expected 3 numbers after '{}', got {}", keyword, words.size() - 1));
        }
        dvec3 v(0.0);
        for (std::size_t i = 1; i < words.size(); ++i) {
            const double x = file_number(words[i], name_, line_);
            if (i <= 3) v[static_cast<int>(i - 1)] = x;
        }
        return v;
    }

    // The colour of a "v" line of six numbers, "v x y z r g b" (the vertex colours
    // MeshLab, ZBrush and photogrammetry tools write): display colours, sRGB-decoded,
    // each clamped into [0, 1]; white for a line of another length.
    glm::vec4 vertex_color(const std::vector<std::string_view>& words) {
        if (words.size() != 7) return glm::vec4(1.0f);
        out_.any_color = true;
        glm::vec4 c(1.0f);
        for (int i = 0; i < 3; ++i) {
            c[i] = float(srgb_to_linear(std::clamp(file_number(words[4 + i], name_, line_), 0.0, 1.0)));
        }
        return c;
    }

    // A "vt" line's u and v (0 where not given; a w must be a number, but is not
    // used). Rounded to float as tinyobjloader, which read them before, did: a
    // textured mesh renders as it did. OBJ's v runs up the image, vkrt's (glTF's)
    // down from its top row.
    glm::dvec2 texture_coordinate(const std::vector<std::string_view>& words) const {
        const std::size_t count = words.size() - 1;
        if (count < 1 || count > 3) fail(fmt::format("expected 1 to 3 numbers after 'vt', got {}", count));
        float uv[2] = {0.0f, 0.0f};
        for (std::size_t i = 1; i < words.size(); ++i) {
            const double x = file_number(words[i], name_, line_);
            if (i <= 2) uv[i - 1] = static_cast<float>(x);
        }
        return {uv[0], 1.0 - double(uv[1])};
    }

    void face(const std::vector<std::string_view>& words) {
        const std::size_t count = words.size() - 1;
        if (count < 3) fail(fmt::format("a face needs at least 3 vertices, got {}", count));
        if (count > kMaxFaceVertices) {
            fail(fmt::format("a face of {} vertices; at most {} are supported", count, kMaxFaceVertices));
        }
        out_.polygons.push_back({out_.corners.size(), count, line_, material_, usemtl_});
        for (std::size_t i = 1; i < words.size(); ++i) out_.corners.push_back(corner(words[i]));
    }

    // v, v/vt, v/vt/vn or v//vn.
    Corner corner(std::string_view word) const {
        Corner c;
        const std::size_t slash = word.find('/');
        c.position = index(word.substr(0, slash), out_.positions.size());
        if (slash == std::string_view::npos) return c;
        word.remove_prefix(slash + 1);
        const std::size_t second = word.find('/');
        if (second != 0) c.uv = index(word.substr(0, second), out_.uvs.size());
        if (second != std::string_view::npos) c.normal = index(word.substr(second + 1), out_.normals.size());
        return c;
    }

    // An index counted from 1, or when negative back from the end of the `count`
    // elements read so far (-1: the last), as an index from 0.
    std::int64_t index(std::string_view text, std::size_t count) const {
        const bool from_end = text.starts_with('-');
        if (from_end || text.starts_with('+')) text.remove_prefix(1);
        std::uint64_t n = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
        if (ec != std::errc() || end != text.data() + text.size() || n == 0 || n > kMaxIndex) {
            // The words of tinyobjloader, which read faces before.
            throw SceneError(
                fmt::format("{}: Failed parse `f' line(e.g. zero value for face index. line {}.)", name_, line_));
        }
        return from_end ? std::int64_t(count) - std::int64_t(n) : std::int64_t(n) - 1;
    }

    void use_material(std::string name) {
        material_ = libraries_ != nullptr ? libraries_->find(name) : -1;
        usemtl_ = out_.usemtl_names.size();
        out_.usemtl_names.push_back(std::move(name));
    }

    // Far beyond any file's count, and far from overflowing an index's arithmetic.
    static constexpr std::uint64_t kMaxIndex = std::uint64_t(1) << 62;

    const std::string& name_;
    MaterialLibraries* libraries_;
    std::size_t line_ = 0;
    int material_ = -1;
    std::size_t usemtl_ = 0;
    ParsedObj out_;
};

// A face's index checked against the `count` elements the file has:
// "<file>:<line>: a face refers to <element> <index from 1>, but the file has <count><plural>".
std::uint32_t checked_index(std::int64_t index, std::size_t count, const char* element, const char* plural,
                            const std::string& name, std::size_t line) {
    if (index < 0 || static_cast<std::uint64_t>(index) >= count) {
        throw SceneError(fmt::format("{}:{}: a face refers to {} {}, but the file has {}{}", name, line, element,
                                     index + 1, count, plural));
    }
    return static_cast<std::uint32_t>(index);
}

// The triangle of three corners of a face on `line`, its indices checked. Texture
// coordinates only where all three corners have them.
IndexedMesh::Face triangle(const std::array<Corner, 3>& c, std::uint32_t material, const IndexedMesh& mesh,
                           const std::string& name, std::size_t line) {
    IndexedMesh::Face f;
    f.material = material;
    for (int i = 0; i < 3; ++i) {
        f.position[i] = checked_index(c[i].position, mesh.positions.size(), "vertex", " vertices", name, line);
        if (c[i].normal != Corner::kNone) {
            f.normal[i] = checked_index(c[i].normal, mesh.normals.size(), "normal", " normals", name, line);
        }
    }
    if (!mesh.colors.empty()) f.color = f.position;
    if (c[0].uv != Corner::kNone && c[1].uv != Corner::kNone && c[2].uv != Corner::kNone) {
        for (int i = 0; i < 3; ++i) {
            f.uv[i] = checked_index(c[i].uv, mesh.uvs.size(), "texture coordinate", "", name, line);
        }
    }
    return f;
}

// Appends a polygon's triangles to the mesh: a fan (v0, vk, vk+1).
void append_fan(const ParsedObj& obj, const Polygon& polygon, std::uint32_t material, const std::string& name,
                IndexedMesh& mesh) {
    const Corner* corners = obj.corners.data() + polygon.first;
    for (std::size_t k = 1; k + 1 < polygon.count; ++k) {
        mesh.faces.push_back(triangle({corners[0], corners[k], corners[k + 1]}, material, mesh, name, polygon.line));
    }
}

// A face's material where the file's are wanted: the one its usemtl found, or an
// error saying why there is none.
std::uint32_t face_material(const Polygon& polygon, const ParsedObj& obj, const MaterialLibraries& libraries,
                            const std::string& name) {
    if (polygon.material >= 0) return static_cast<std::uint32_t>(polygon.material);
    const std::string& used = obj.usemtl_names[polygon.usemtl];
    std::string why;
    if (used.empty()) {
        why = "no usemtl before it";
    } else if (!libraries.unreadable().empty()) {
        why = fmt::format("usemtl {}, and mtllib {} is not there", json::quote_user(used),
                          json::quote_user(libraries.unreadable().front()));
    } else if (libraries.names().empty()) {
        why = fmt::format("usemtl {}, but the file names no mtllib", json::quote_user(used));
    } else {
        why = fmt::format("usemtl {} is not defined in mtllib {}", json::quote_user(used),
                          json::quote_user(libraries.names().front()));
    }
    throw SceneError(fmt::format(
        "{}:{}: the face has no material ({}); give the mesh object a \"material\" for the whole mesh", name,
        polygon.line, why));
}

// The libraries' materials as vkrt's, with their map_Kd files.
void add_materials(const MaterialLibraries& libraries, const std::string& name, std::vector<std::string>& warnings,
                   IndexedMesh& mesh) {
    for (const tinyobj::material_t& m : libraries.materials()) {
        mesh.materials.push_back(from_mtl(m, name, warnings));
        mesh.material_textures.push_back(m.diffuse_texname);
    }
}

IndexedMesh read_obj(const std::filesystem::path& file, std::vector<std::string>* material_warnings) {
    const std::string name = file.string();
    const std::string text = read_text(file, name, "mesh");
    std::optional<MaterialLibraries> libraries;
    if (material_warnings != nullptr) libraries.emplace(file);
    ParsedObj obj = ObjParser(name, libraries ? &*libraries : nullptr).parse(text);
    if (libraries && libraries->names().size() > 1) {
        material_warnings->push_back(fmt::format(
            "{}: names {} MTL files; tinyobjloader reads the first one of them that exists", name,
            libraries->names().size()));
    }
    if (obj.polygons.empty()) throw SceneError(fmt::format("{}: the file has no faces (no 'f' lines)", name));

    IndexedMesh mesh;
    mesh.positions = std::move(obj.positions);
    mesh.normals = std::move(obj.normals);
    mesh.uvs = std::move(obj.uvs);
    if (obj.any_color) mesh.colors = std::move(obj.colors);
    if (libraries) add_materials(*libraries, name, *material_warnings, mesh);
    for (const Polygon& polygon : obj.polygons) {
        const std::uint32_t material =
            libraries ? face_material(polygon, obj, *libraries, name) : IndexedMesh::kNoMaterial;
        append_fan(obj, polygon, material, name, mesh);
    }
    return mesh;
}

}  // namespace

IndexedMesh load_obj(const std::filesystem::path& file) { return read_obj(file, nullptr); }

IndexedMesh load_obj_with_materials(const std::filesystem::path& file, std::vector<std::string>& warnings) {
    return read_obj(file, &warnings);
}

MeshObject read_mesh_object(const json::Node& n, const MaterialLookup& material, Scene& scene) {
    n.allow_only({"type", "file", "material", "smooth", "transform"});
    const json::Node file = n.required("file");
    const std::string relative = file.string();  // names the file's materials
    const std::filesystem::path path = file.file_path();

    MeshObject out;
    MeshOptions& options = out.options;
    const std::optional<json::Node> given = n.find("material");
    if (given) options.material = material(*given);
    if (auto smooth = n.find("smooth")) options.smooth = smooth->boolean();

    IndexedMesh& mesh = out.mesh;
    std::vector<std::string> warnings;
    try {
        mesh = given ? load_obj(path) : load_obj_with_materials(path, warnings);
    } catch (const SceneError& e) {
        // The OBJ's own message ("<obj>:<line>: ...") after the scene's path to it.
        file.fail(e.what());
    }
    // The file's materials join the scene's, named after the file: JSON objects
    // cannot refer to them, and two meshes' materials of one name stay apart.
    for (std::size_t i = 0; i < mesh.materials.size(); ++i) {
        options.face_materials.push_back(static_cast<std::uint32_t>(scene.materials.size()));
        Material named = mesh.materials[i];
        named.name = fmt::format("{}:{}", relative, named.name);
        // map_Kd, relative to the OBJ file (where tinyobjloader found its MTL file).
        if (const std::string& texture = mesh.material_textures.at(i); !texture.empty()) {
            const std::string element = fmt::format("{}: {}: material {} map_Kd", n.file(), file.path(),
                                                    json::quote_user(mesh.materials[i].name));
            named.texture = load_texture(scene, path.parent_path() / texture, Encoding::SrgbUnlessFloat, element);
        }
        scene.materials.push_back(std::move(named));
    }
    for (const std::string& w : warnings) scene.warnings.push_back(fmt::format("{}: {}: {}", n.file(), n.path(), w));
    return out;
}

void read_mesh(const json::Node& n, const MaterialLookup& material, Scene& scene) {
    const std::optional<json::Node> transform = n.find("transform");
    const Transform t = transform ? read_transform(*transform) : Transform{};
    MeshObject object = read_mesh_object(n, material, scene);
    add_mesh(n, std::move(object.mesh), t, transform, object.options, scene);
}

}  // namespace vkrt
