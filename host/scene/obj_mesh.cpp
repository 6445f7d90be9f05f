// OBJ files are read in two passes over the text. Our own pass checks every line
// that carries geometry and takes the numbers from it; tinyobjloader then reads the
// structure (faces, their index forms v, v/t, v/t/n, v//n and negative relative
// indices). The first pass exists because tinyobjloader reads a malformed number
// ("nan", "1,5", "abc") as 0 without a word, and some valid ones wrongly ("0e400"
// becomes NaN): a model would silently change shape instead of being refused.
#include "scene/obj_mesh.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include "scene/read_text.hpp"
#include "scene/scene_error.hpp"
#include "scene/vec_math.hpp"

namespace vkrt {
namespace {

using glm::dvec3;

// tinyobjloader keeps a face's vertex count in an unsigned char.
constexpr std::size_t kMaxFaceVertices = 255;

// The words of one OBJ or MTL line; a comment runs from '#' to the end of the line.
std::vector<std::string_view> words_of(std::string_view line) {
    line = line.substr(0, line.find('#'));
    std::vector<std::string_view> words;
    std::size_t at = 0;
    while (true) {
        at = line.find_first_not_of(" \t\r", at);
        if (at == std::string_view::npos) break;
        const std::size_t end = std::min(line.find_first_of(" \t\r", at), line.size());
        words.push_back(line.substr(at, end - at));
        at = end;
    }
    return words;
}

// Calls statement(line number from 1, words) for every line of the text with words.
template <class F>
void for_each_statement(std::string_view text, F&& statement) {
    std::size_t start = 0, line = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        ++line;
        const std::vector<std::string_view> words = words_of(text.substr(start, end - start));
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

// What the first pass takes from the file.
struct Scanned {
    std::vector<dvec3> positions;
    std::vector<dvec3> normals;
    std::vector<std::size_t> face_lines;  // the line of each face, in file order
    std::vector<std::string> face_usemtl;  // the usemtl name before each face ("" for none)
    std::vector<std::string> mtllibs;      // every file an mtllib line names
};

class Scanner {
public:
    explicit Scanner(const std::string& name) : name_(name) {}

    Scanned scan(std::string_view text) {
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
        if (words[0] == "v") {
            out_.positions.push_back(triple(words, "v"));
        } else if (words[0] == "vn") {
            out_.normals.push_back(triple(words, "vn"));
        } else if (words[0] == "f") {
            const std::size_t n = words.size() - 1;
            if (n < 3) fail(fmt::format("a face needs at least 3 vertices, got {}", n));
            if (n > kMaxFaceVertices) {
                fail(fmt::format("a face of {} vertices; at most {} are supported", n, kMaxFaceVertices));
            }
            out_.face_lines.push_back(line_);
            out_.face_usemtl.push_back(usemtl_);
        } else if (words[0] == "usemtl" && words.size() > 1) {
            usemtl_ = std::string(words[1]);
        } else if (words[0] == "mtllib") {
            for (std::size_t i = 1; i < words.size(); ++i) out_.mtllibs.emplace_back(words[i]);
        }
        // Every other statement (g, o, s, l, p, ...) carries nothing we use; vt is counted by
        // tinyobjloader alone.
    }

    // The first three numbers of a "v" or "vn" line; the rest (w, vertex colours)
    // must be numbers too, but are not used.
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

    const std::string& name_;
    std::size_t line_ = 0;
    std::string usemtl_;
    Scanned out_;
};

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

IndexedMesh read_obj(const std::filesystem::path& file, std::vector<std::string>* material_warnings) {
    const std::string name = file.string();
    const std::string text = read_text(file, name, "mesh");
    Scanned scanned = Scanner(name).scan(text);

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warning;
    std::string error;
    std::istringstream stream(text);
    // The MTL files beside the OBJ only when its materials are wanted; otherwise
    // mtllib lines are skipped rather than opened (the scene gives the material).
    // tinyobjloader's warnings concern materials (quoted below where a face lacks
    // one) or indices out of range, which are checked below with the line named.
    // No triangulation: its quads are split along the shorter diagonal and larger
    // polygons by ear clipping that skips what it cannot use; a fan is predictable.
    // The directory with its separator ("box.obj" alone is in "./", not "/").
    const std::filesystem::path dir = file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path();
    std::vector<std::string> unreadable;  // mtllib files that are not there
    if (material_warnings != nullptr) {
        for (const std::string& lib : scanned.mtllibs) {
            if (std::filesystem::is_regular_file(dir / lib)) {
                check_mtl(dir / lib);
            } else {
                unreadable.push_back(lib);
            }
        }
        if (scanned.mtllibs.size() > 1) {
            material_warnings->push_back(fmt::format(
                "{}: names {} MTL files; tinyobjloader reads the first one of them that exists", name,
                scanned.mtllibs.size()));
        }
    }
    tinyobj::MaterialFileReader mtl_reader(dir.string() + "/");
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &stream,
                                     material_warnings != nullptr ? &mtl_reader : nullptr, /*triangulate=*/false,
                                     /*default_vcols_fallback=*/false);
    if (!ok) throw SceneError(fmt::format("{}: {}", name, one_line(error)));

    std::size_t faces = 0;
    for (const tinyobj::shape_t& shape : shapes) faces += shape.mesh.num_face_vertices.size();
    if (attrib.vertices.size() != 3 * scanned.positions.size() ||
        attrib.normals.size() != 3 * scanned.normals.size() || faces != scanned.face_lines.size()) {
        // Both passes read the same lines; a difference means they read it differently.
        throw SceneError(fmt::format(
            "{}: tinyobjloader read {} vertices, {} normals and {} faces where the file has {}, {} and {}", name,
            attrib.vertices.size() / 3, attrib.normals.size() / 3, faces, scanned.positions.size(),
            scanned.normals.size(), scanned.face_lines.size()));
    }
    if (faces == 0) throw SceneError(fmt::format("{}: the file has no faces (no 'f' lines)", name));

    IndexedMesh mesh;
    mesh.positions = std::move(scanned.positions);
    mesh.normals = std::move(scanned.normals);
    // OBJ's v runs up the image, vkrt's (glTF's) down from its top row.
    for (std::size_t i = 0; i + 1 < attrib.texcoords.size(); i += 2) {
        const glm::dvec2 uv(attrib.texcoords[i], 1.0 - double(attrib.texcoords[i + 1]));
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) {
            throw SceneError(fmt::format("{}: texture coordinate {} is not finite", name, i / 2 + 1));
        }
        mesh.uvs.push_back(uv);
    }
    const auto position_of = [&](int index, std::size_t line) {
        if (index < 0 || static_cast<std::size_t>(index) >= mesh.positions.size()) {
            throw SceneError(fmt::format("{}:{}: a face refers to vertex {}, but the file has {} vertices", name, line,
                                         index + 1, mesh.positions.size()));
        }
        return static_cast<std::uint32_t>(index);
    };
    const auto normal_of = [&](int index, std::size_t line) {
        if (index == -1) return IndexedMesh::kNoNormal;  // the face gave none
        if (index < 0 || static_cast<std::size_t>(index) >= mesh.normals.size()) {
            throw SceneError(fmt::format("{}:{}: a face refers to normal {}, but the file has {} normals", name, line,
                                         index + 1, mesh.normals.size()));
        }
        return static_cast<std::uint32_t>(index);
    };

    if (material_warnings != nullptr) {
        for (const tinyobj::material_t& m : materials) {
            mesh.materials.push_back(from_mtl(m, name, *material_warnings));
            mesh.material_textures.push_back(m.diffuse_texname);
        }
    }
    std::size_t face = 0;
    for (const tinyobj::shape_t& shape : shapes) {
        std::size_t first = 0;
        for (std::size_t face_in_shape = 0; face_in_shape < shape.mesh.num_face_vertices.size(); ++face_in_shape) {
            const unsigned char count = shape.mesh.num_face_vertices[face_in_shape];
            const std::size_t line = scanned.face_lines[face++];
            std::uint32_t material = IndexedMesh::kNoMaterial;
            if (material_warnings != nullptr) {
                const int id = shape.mesh.material_ids[face_in_shape];
                if (id < 0 || static_cast<std::size_t>(id) >= mesh.materials.size()) {
                    const std::string& used = scanned.face_usemtl[face - 1];
                    std::string why;
                    if (used.empty()) {
                        why = "no usemtl before it";
                    } else if (!unreadable.empty()) {
                        why = fmt::format("usemtl {}, and mtllib {} is not there", json::quote_user(used),
                                          json::quote_user(unreadable.front()));
                    } else if (scanned.mtllibs.empty()) {
                        why = fmt::format("usemtl {}, but the file names no mtllib", json::quote_user(used));
                    } else {
                        why = fmt::format("usemtl {} is not defined in mtllib {}", json::quote_user(used),
                                          json::quote_user(scanned.mtllibs.front()));
                    }
                    throw SceneError(fmt::format(
                        "{}:{}: the face has no material ({}); give the mesh object a \"material\" for the "
                        "whole mesh",
                        name, line, why));
                }
                material = static_cast<std::uint32_t>(id);
            }
            const auto corner = [&](std::size_t k) { return shape.mesh.indices[first + k]; };
            for (std::size_t k = 1; k + 1 < count; ++k) {
                IndexedMesh::Face f;
                f.material = material;
                const tinyobj::index_t c[3] = {corner(0), corner(k), corner(k + 1)};
                for (int i = 0; i < 3; ++i) {
                    f.position[i] = position_of(c[i].vertex_index, line);
                    f.normal[i] = normal_of(c[i].normal_index, line);
                }
                // Texture coordinates where all three corners have them.
                if (c[0].texcoord_index >= 0 && c[1].texcoord_index >= 0 && c[2].texcoord_index >= 0) {
                    for (int i = 0; i < 3; ++i) {
                        if (static_cast<std::size_t>(c[i].texcoord_index) >= mesh.uvs.size()) {
                            throw SceneError(fmt::format("{}:{}: a face refers to texture coordinate {}, but the file "
                                                         "has {}",
                                                         name, line, c[i].texcoord_index + 1, mesh.uvs.size()));
                        }
                        f.uv[i] = static_cast<std::uint32_t>(c[i].texcoord_index);
                    }
                }
                mesh.faces.push_back(f);
            }
            first += count;
        }
    }
    return mesh;
}

}  // namespace

IndexedMesh load_obj(const std::filesystem::path& file) { return read_obj(file, nullptr); }

IndexedMesh load_obj_with_materials(const std::filesystem::path& file, std::vector<std::string>& warnings) {
    return read_obj(file, &warnings);
}

void read_mesh(const json::Node& n, const MaterialLookup& material, Scene& scene) {
    n.allow_only({"type", "file", "material", "smooth", "transform"});
    const json::Node file = n.required("file");
    const std::string relative = file.string();  // names the file's materials
    const std::filesystem::path path = file.file_path();

    MeshOptions options;
    const std::optional<json::Node> given = n.find("material");
    if (given) options.material = material(*given);
    if (auto smooth = n.find("smooth")) options.smooth = smooth->boolean();
    const std::optional<json::Node> transform = n.find("transform");
    const Transform t = transform ? read_transform(*transform) : Transform{};

    IndexedMesh mesh;
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
    add_mesh(n, std::move(mesh), t, transform, options, scene);
}

}  // namespace vkrt
