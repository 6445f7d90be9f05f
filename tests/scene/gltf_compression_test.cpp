// Compressed and quantized glTF files (host/scene/gltf_file.cpp, gltf_draco.cpp,
// gltf_meshopt.cpp, gltf_accessor.cpp): the variants draco_transcoder and gltfpack
// wrote of the Blender scenes (scenes/gltf/variants/) decode to the originals'
// triangles within their quantization steps; every mode and filter of
// EXT_meshopt_compression decodes what libmeshoptimizer's encoders wrote; broken
// streams, and extensions a file requires that vkrt does not read, are refused in
// one line naming the file and the element.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "scene/gltf_meshopt.hpp"
#include "scene/load_scene.hpp"
#include "scene/scene_error.hpp"
#include "test_support.hpp"

namespace {

using glm::dvec2;
using glm::dvec3;
using vkrt::Scene;
using vkrt::Triangle;
namespace fs = std::filesystem;
namespace test = vkrt::test;

// ------------------------------------------------------------------ files

std::string read_file(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Glb {
    nlohmann::json json;
    std::string bin;
};

// A .glb's JSON and binary chunks (glTF 2.0, 4.4), as the tools wrote them.
Glb read_glb(const fs::path& file) {
    const std::string bytes = read_file(file);
    std::uint32_t json_length = 0, bin_length = 0;
    std::memcpy(&json_length, bytes.data() + 12, 4);
    Glb glb;
    glb.json = nlohmann::json::parse(bytes.substr(20, json_length));
    const std::size_t bin_at = 20 + json_length;
    if (bin_at + 8 <= bytes.size()) {
        std::memcpy(&bin_length, bytes.data() + bin_at, 4);
        glb.bin = bytes.substr(bin_at + 8, bin_length);
    }
    return glb;
}

fs::path write_glb(const fs::path& file, const nlohmann::json& json, std::string bin) {
    std::string text = json.dump();
    while (text.size() % 4) text += ' ';
    while (bin.size() % 4) bin += '\0';
    std::string out;
    const auto u32 = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    u32(0x46546C67u);  // "glTF"
    u32(2);
    u32(static_cast<std::uint32_t>(12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size())));
    u32(static_cast<std::uint32_t>(text.size()));
    u32(0x4E4F534Au);  // "JSON"
    out += text;
    if (!bin.empty()) {
        u32(static_cast<std::uint32_t>(bin.size()));
        u32(0x004E4942u);  // "BIN\0"
        out += bin;
    }
    std::ofstream(file, std::ios::binary) << out;
    return file;
}

fs::path variant(const std::string& name) { return test::source_dir() / "scenes" / "gltf" / "variants" / name; }
fs::path original(const std::string& name) { return test::source_dir() / "scenes" / "gltf" / name; }

// A copy of a shipped .glb as `name`, edited.
fs::path edited(const fs::path& from, const std::string& name, const std::function<void(Glb&)>& edit) {
    Glb glb = read_glb(from);
    edit(glb);
    return write_glb(test::temp_dir("gltf_compression_" + name) / (name + ".glb"), glb.json, glb.bin);
}

// ------------------------------------------------------------------ variants

double extent(const Scene& s) {
    dvec3 lo(1e300), hi(-1e300);
    for (const Triangle& t : s.triangles) {
        for (const dvec3& v : t.vertices) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
    }
    const dvec3 d = hi - lo;
    return std::max({d.x, d.y, d.z});
}

// Where a texture is read: a vertex's coordinates through its material's transform
// (gltfpack moves its dequantization there, as KHR_texture_transform).
dvec2 texture_point(const Scene& s, const Triangle& t, int k) {
    const std::array<double, 6>& m = s.materials[t.material].uv_transform;
    const dvec2 uv = (*t.uvs)[static_cast<std::size_t>(k)];
    return {m[0] * uv.x + m[1] * uv.y + m[2], m[3] * uv.x + m[4] * uv.y + m[5]};
}

double uv_extent(const Scene& s) {
    double lo = 1e300, hi = -1e300;
    for (const Triangle& t : s.triangles) {
        if (!t.uvs) continue;
        for (int k = 0; k < 3; ++k) {
            const dvec2 uv = texture_point(s, t, k);
            lo = std::min({lo, uv.x, uv.y});
            hi = std::max({hi, uv.x, uv.y});
        }
    }
    return hi - lo;
}

double max_abs(dvec3 d) { return std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}); }

double angle(dvec3 a, dvec3 b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0));
}

// How a tool quantizes (its defaults): bits for positions over the largest extent
// of a primitive (Draco) or the scene (gltfpack), a single range for all three
// axes; bits for texture coordinates likewise; normals in 8 bits.
struct Variant {
    const char* original;
    const char* file;
    int position_bits;
    int uv_bits;
    // The largest angle, in radians, between a decoded normal and its original.
    // gltfpack stores each component as a normalized byte, at most h = 0.5/127 off,
    // tilting a unit normal by at most sqrt(3) h (0.0069 rad). Octahedral
    // coordinates (Draco's, and meshopt's OCTAHEDRAL filter) of 8 bits over [-1, 1]
    // are each at most h ~ 1/255 off, and the third coordinate, 1 - |x| - |y|, 2h:
    // a point of the octahedron at most sqrt(6) h away, and since the octahedron's
    // points lie at least 1/sqrt(3) from the centre, a direction at most
    // sqrt(3) sqrt(6) h = 3 sqrt(2) h off (0.0167 rad, with h = 1/254).
    double normal_angle;
    bool keeps_emission;  // draco_transcoder drops KHR_materials_emissive_strength
};

void PrintTo(const Variant& v, std::ostream* os) { *os << v.file; }

// Half a quantization step of `bits` over `range`, and float rounding of values up to 8.
double half_step(double range, int bits) { return range / (2.0 * ((1 << bits) - 1)) + 8.0 * 0x1p-23; }

class Variants : public ::testing::TestWithParam<Variant> {};

// Each original triangle has one decoded triangle of the same material within half
// a quantization step per coordinate, its vertices in the same turning order (the
// first may differ); and no decoded triangle is left over.
TEST_P(Variants, DecodeToTheOriginalTrianglesWithinAQuantizationStep) {
    const Variant& v = GetParam();
    const Scene a = vkrt::load_scene(original(v.original));
    const Scene b = vkrt::load_scene(variant(v.file));
    const double position_bound = half_step(extent(a), v.position_bits);
    const double uv_bound = half_step(uv_extent(a), v.uv_bits);
    ASSERT_EQ(a.triangles.size(), b.triangles.size());

    // The decoded triangles by the cell of their centroid.
    const double cell = 0.05;
    const auto key = [&](dvec3 p) {
        return std::make_tuple(std::llround(p.x / cell), std::llround(p.y / cell), std::llround(p.z / cell));
    };
    std::map<std::tuple<long long, long long, long long>, std::vector<std::size_t>> cells;
    for (std::size_t i = 0; i < b.triangles.size(); ++i) {
        const Triangle& t = b.triangles[i];
        cells[key((t.vertices[0] + t.vertices[1] + t.vertices[2]) / 3.0)].push_back(i);
    }
    std::vector<bool> used(b.triangles.size(), false);
    double worst_position = 0.0, worst_normal = 0.0, worst_uv = 0.0;
    std::size_t unmatched = 0;
    for (const Triangle& t : a.triangles) {
        const dvec3 c = (t.vertices[0] + t.vertices[1] + t.vertices[2]) / 3.0;
        const auto [x, y, z] = key(c);
        const vkrt::Material& ma = a.materials[t.material];
        std::optional<std::pair<std::size_t, int>> found;  // triangle, rotation
        double found_error = 0.0;
        for (long long dx = -1; dx <= 1 && !found; ++dx) {
            for (long long dy = -1; dy <= 1 && !found; ++dy) {
                for (long long dz = -1; dz <= 1 && !found; ++dz) {
                    const auto it = cells.find({x + dx, y + dy, z + dz});
                    if (it == cells.end()) continue;
                    for (std::size_t i : it->second) {
                        if (used[i]) continue;
                        const Triangle& u = b.triangles[i];
                        const vkrt::Material& mb = b.materials[u.material];
                        if (max_abs(ma.metallic_roughness->base_color - mb.metallic_roughness->base_color) > 1e-6 ||
                            std::abs(ma.metallic_roughness->roughness - mb.metallic_roughness->roughness) > 1e-6 ||
                            std::abs(ma.metallic_roughness->metallic - mb.metallic_roughness->metallic) > 1e-6) {
                            continue;
                        }
                        for (int r = 0; r < 3 && !found; ++r) {
                            double e = 0.0;
                            for (int k = 0; k < 3; ++k) e = std::max(e, max_abs(t.vertices[k] - u.vertices[(k + r) % 3]));
                            if (e <= position_bound) {
                                found = {i, r};
                                found_error = e;
                            }
                        }
                        if (found) break;
                    }
                }
            }
        }
        if (!found) {
            ++unmatched;
            continue;
        }
        const auto [i, r] = *found;
        used[i] = true;
        const Triangle& u = b.triangles[i];
        worst_position = std::max(worst_position, found_error);
        ASSERT_EQ(t.normals.has_value(), u.normals.has_value());
        // gltfpack keeps texture coordinates only where a texture reads them.
        if (ma.texture) {
            ASSERT_TRUE(u.uvs.has_value());
        }
        for (int k = 0; k < 3; ++k) {
            if (t.normals) worst_normal = std::max(worst_normal, angle((*t.normals)[k], (*u.normals)[(k + r) % 3]));
            if (t.uvs && u.uvs) {
                const dvec2 d = texture_point(a, t, k) - texture_point(b, u, (k + r) % 3);
                worst_uv = std::max({worst_uv, std::abs(d.x), std::abs(d.y)});
            }
        }
        if (v.keeps_emission) {
            EXPECT_LE(max_abs(ma.emission - b.materials[u.material].emission), 1e-5 * max_abs(ma.emission));
        }
    }
    std::printf("%s: %zu triangles; positions off by %.3g (bound %.3g), normals by %.3g rad (bound %.3g), texture "
                "coordinates by %.3g (bound %.3g)\n",
                v.file, a.triangles.size(), worst_position, position_bound, worst_normal, v.normal_angle, worst_uv,
                uv_bound);
    EXPECT_EQ(unmatched, 0u) << "original triangles without a decoded one within " << position_bound;
    EXPECT_LE(worst_normal, v.normal_angle);
    EXPECT_LE(worst_uv, uv_bound);
}

// draco_transcoder: positions 11 bits, texture coordinates 10 (its defaults);
// gltfpack: 14 and 12.
constexpr double kByteNormal = 0.0069;
constexpr double kOctahedralNormal = 0.0167;
INSTANTIATE_TEST_SUITE_P(
    Tools, Variants,
    ::testing::Values(Variant{"still_life.glb", "still_life_draco.glb", 11, 10, kOctahedralNormal, false},
                      Variant{"metals.glb", "metals_draco.glb", 11, 10, kOctahedralNormal, false},
                      Variant{"still_life.glb", "still_life_quantized.glb", 14, 12, kByteNormal, true},
                      Variant{"metals.glb", "metals_quantized.glb", 14, 12, kByteNormal, true},
                      Variant{"still_life.glb", "still_life_meshopt.glb", 14, 12, kOctahedralNormal, true},
                      Variant{"metals.glb", "metals_meshopt.glb", 14, 12, kOctahedralNormal, true},
                      Variant{"still_life.glb", "still_life_meshopt_fallback.glb", 14, 12, kByteNormal, true}),
    [](const ::testing::TestParamInfo<Variant>& param) {
        std::string name = fs::path(param.param.file).stem().string();
        std::replace(name.begin(), name.end(), '.', '_');
        return name;
    });


// ------------------------------------------------------------------ required extensions

// The message every refusal of a required extension gives, and nothing before it.
std::string required_message(const fs::path& file, const std::string& name) {
    return fmt::format("{}: the file requires the extension {}, which vkrt does not read", file.string(), name);
}

TEST(RequiredExtensions, AnExtensionVkrtDoesNotReadIsRefusedByName) {
    const fs::path file = edited(original("still_life.glb"), "requires_foo", [](Glb& g) {
        g.json["extensionsUsed"].push_back("KHR_foo");
        g.json["extensionsRequired"] = {"KHR_materials_emissive_strength", "KHR_foo"};
    });
    EXPECT_EQ(test::load_error_of(file), required_message(file, "KHR_foo"));
}

// Refused by name before anything else is said of the file, however else it is
// broken: an indices accessor without a buffer view (tinygltf's "accessor[0]
// invalid bufferView", as a Draco file read by a loader without Draco says), a
// buffer file that is not there, a binary chunk shorter than its buffer.
TEST(RequiredExtensions, TheRefusalComesBeforeAnyOtherMessage) {
    const fs::path draco_without_extension = edited(variant("still_life_draco.glb"), "foo_draco", [](Glb& g) {
        g.json["extensionsRequired"] = {"KHR_foo"};
        for (auto& mesh : g.json["meshes"]) {
            for (auto& prim : mesh["primitives"]) prim.erase("extensions");
        }
    });
    EXPECT_EQ(test::load_error_of(draco_without_extension), required_message(draco_without_extension, "KHR_foo"));
    const fs::path missing_buffer = edited(original("still_life.glb"), "foo_missing_buffer", [](Glb& g) {
        g.json["extensionsRequired"] = {"EXT_foo"};
        g.json["buffers"][0]["uri"] = "nowhere.bin";
    });
    EXPECT_EQ(test::load_error_of(missing_buffer), required_message(missing_buffer, "EXT_foo"));
    const fs::path short_chunk = edited(original("still_life.glb"), "foo_short_chunk", [](Glb& g) {
        g.json["extensionsRequired"] = {"EXT_foo"};
        g.bin.resize(64);
    });
    EXPECT_EQ(test::load_error_of(short_chunk), required_message(short_chunk, "EXT_foo"));
    // The same in a .gltf: JSON text, its buffer a data URI.
    Glb g = read_glb(original("still_life.glb"));
    g.json["extensionsRequired"] = {"KHR_bar"};
    g.json["accessors"][0].erase("bufferView");
    const fs::path text = test::temp_dir("gltf_compression_foo_text") / "bar.gltf";
    std::ofstream(text) << g.json.dump();
    EXPECT_EQ(test::load_error_of(text), required_message(text, "KHR_bar"));
}

TEST(RequiredExtensions, AMalformedListIsNamed) {
    const fs::path file = edited(original("still_life.glb"), "required_string", [](Glb& g) {
        g.json["extensionsRequired"] = "KHR_foo";
    });
    test::expect_error_message(test::load_error_of(file), file.string() + ": extensionsRequired: ",
                               {"expected an array of extension names"});
    const fs::path number = edited(original("still_life.glb"), "required_number", [](Glb& g) {
        g.json["extensionsRequired"] = {7};
    });
    test::expect_error_message(test::load_error_of(number), number.string() + ": extensionsRequired[0]: ",
                               {"expected an extension name"});
}

// ------------------------------------------------------------------ Draco

// The sphere of the still life: meshes[1], its stream in bufferViews[1].
const char* const kDracoSphere = "meshes[1].primitives[0].extensions.KHR_draco_mesh_compression";

std::size_t view_offset(const Glb& g, int view) { return g.json["bufferViews"][view].value("byteOffset", std::size_t(0)); }

TEST(Draco, ATruncatedStreamIsNamed) {
    const fs::path file = edited(variant("still_life_draco.glb"), "draco_truncated", [](Glb& g) {
        auto& length = g.json["bufferViews"][1]["byteLength"];
        length = length.get<std::size_t>() / 2;
    });
    test::expect_error_message(test::load_error_of(file), file.string() + ": " + kDracoSphere + ": ",
                               {"the Draco stream in bufferViews[1] cannot be decoded"});
}

TEST(Draco, AStreamThatIsNotDracoIsNamed) {
    const fs::path file = edited(variant("still_life_draco.glb"), "draco_magic", [](Glb& g) {
        std::memcpy(g.bin.data() + view_offset(g, 1), "DRACX", 5);
    });
    test::expect_error_message(test::load_error_of(file), file.string() + ": " + kDracoSphere + ": ",
                               {"the Draco stream in bufferViews[1] cannot be decoded", "Not a Draco file"});
}

TEST(Draco, AttributesAndAccessorsThatDoNotMatchTheStreamAreNamed) {
    const fs::path id = edited(variant("still_life_draco.glb"), "draco_id", [](Glb& g) {
        g.json["meshes"][1]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 9;
    });
    test::expect_error_message(test::load_error_of(id), id.string() + ": " + kDracoSphere + ".attributes.NORMAL: ",
                               {"the Draco stream has no attribute of id 9"});
    const fs::path count = edited(variant("still_life_draco.glb"), "draco_count", [](Glb& g) {
        g.json["accessors"][g.json["meshes"][1]["primitives"][0]["attributes"]["POSITION"].get<int>()]["count"] = 3;
    });
    test::expect_error_message(test::load_error_of(count), count.string() + ": " + kDracoSphere + ".attributes.POSITION: ",
                               {"the Draco stream holds", "points;", "counts 3"});
    const fs::path type = edited(variant("still_life_draco.glb"), "draco_type", [](Glb& g) {
        g.json["accessors"][g.json["meshes"][1]["primitives"][0]["attributes"]["TEXCOORD_0"].get<int>()]["type"] = "VEC3";
    });
    test::expect_error_message(test::load_error_of(type), type.string() + ": " + kDracoSphere + ".attributes.TEXCOORD_0: ",
                               {"the Draco attribute has 2 components", "has 3"});
    const fs::path missing = edited(variant("still_life_draco.glb"), "draco_missing", [](Glb& g) {
        g.json["meshes"][1]["primitives"][0]["attributes"].erase("NORMAL");
    });
    test::expect_error_message(test::load_error_of(missing), missing.string() + ": " + kDracoSphere + ".attributes.NORMAL: ",
                               {"the primitive has no NORMAL attribute"});
}

// Bytes of a stream changed one at a time, and streams cut short: each file loads
// or is refused in one line naming the file, never a crash.
TEST(Draco, DamagedStreamsLoadOrAreRefusedInOneLine) {
    const Glb whole = read_glb(variant("still_life_draco.glb"));
    const std::size_t at = view_offset(whole, 1);
    const std::size_t length = whole.json["bufferViews"][1]["byteLength"];
    const fs::path file = test::temp_dir("gltf_compression_draco_damaged") / "damaged.glb";
    std::size_t refused = 0, loaded = 0;
    const auto attempt = [&](const Glb& g) {
        write_glb(file, g.json, g.bin);
        try {
            vkrt::load_scene(file);
            ++loaded;
        } catch (const vkrt::SceneError& e) {
            ++refused;
            test::expect_error_message(e.what(), file.string() + ": ", {});
        }
    };
    for (std::size_t i = 0; i < length; i += 13) {
        Glb g = whole;
        g.bin[at + i] = static_cast<char>(g.bin[at + i] ^ 0x5A);
        attempt(g);
    }
    for (std::size_t cut = 0; cut < length; cut += 97) {
        Glb g = whole;
        g.json["bufferViews"][1]["byteLength"] = cut;
        attempt(g);
    }
    std::printf("damaged Draco streams: %zu loaded, %zu refused\n", loaded, refused);
    EXPECT_GT(refused, 0u);
}


// ------------------------------------------------------------------ meshopt

using vkrt::gltf::MeshoptView;

// A model holding `encoded` in buffers[0] and one view of `count` elements of
// `stride` bytes, decoded as `mode` and `filter`; the decoded bytes.
std::vector<unsigned char> meshopt_decoded(const std::vector<unsigned char>& encoded, std::size_t count, std::size_t stride,
                                           MeshoptView::Mode mode, MeshoptView::Filter filter) {
    tinygltf::Model model;
    model.buffers.resize(1);
    model.buffers[0].data = encoded;
    model.bufferViews.resize(1);
    vkrt::gltf::MeshoptViews views;
    MeshoptView v;
    v.byte_length = encoded.size();
    v.byte_stride = stride;
    v.count = count;
    v.mode = mode;
    v.filter = filter;
    views.views.push_back(v);
    vkrt::gltf::decode_meshopt(model, views, "model.gltf");
    const tinygltf::BufferView& view = model.bufferViews[0];
    EXPECT_EQ(view.byteOffset, 0u);
    EXPECT_EQ(view.byteLength, count * stride);
    return model.buffers.at(static_cast<std::size_t>(view.buffer)).data;
}

template <typename T>
std::vector<unsigned char> encode_vertices(const std::vector<T>& elements, std::size_t stride) {
    const std::size_t count = elements.size() * sizeof(T) / stride;
    std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(count, stride));
    out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), elements.data(), count, stride));
    return out;
}

template <typename T>
std::vector<T> as(const std::vector<unsigned char>& bytes) {
    std::vector<T> out(bytes.size() / sizeof(T));
    std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
    return out;
}

// 40 elements: more than the 16 of a group, so that deltas run across groups.
constexpr std::size_t kElements = 40;

TEST(Meshopt, AttributesDecodeToTheirBytes) {
    std::vector<std::uint32_t> data(kElements * 3);
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint32_t>(i * 2654435761u);
    const auto decoded = meshopt_decoded(encode_vertices(data, 12), kElements, 12, MeshoptView::Mode::Attributes,
                                         MeshoptView::Filter::None);
    EXPECT_EQ(as<std::uint32_t>(decoded), data);
}

TEST(Meshopt, TrianglesAndIndicesDecodeToTheirIndices) {
    std::vector<unsigned int> indices;
    for (unsigned int i = 0; i < kElements; ++i) indices.insert(indices.end(), {i, i + 1, 50 + (i * 7) % 50});
    std::vector<unsigned char> triangles(meshopt_encodeIndexBufferBound(indices.size(), 100));
    triangles.resize(meshopt_encodeIndexBuffer(triangles.data(), triangles.size(), indices.data(), indices.size()));
    std::vector<unsigned char> sequence(meshopt_encodeIndexSequenceBound(indices.size(), 100));
    sequence.resize(meshopt_encodeIndexSequence(sequence.data(), sequence.size(), indices.data(), indices.size()));
    const std::vector<std::uint16_t> shorts(indices.begin(), indices.end());
    // The triangle codec may start a triangle at another of its corners (turning
    // the same way): each is compared from its smallest index.
    const auto turned = [](auto list) {
        for (std::size_t i = 0; i < list.size(); i += 3) {
            const auto first = std::min_element(list.begin() + long(i), list.begin() + long(i) + 3);
            std::rotate(list.begin() + long(i), first, list.begin() + long(i) + 3);
        }
        return list;
    };
    EXPECT_EQ(turned(as<std::uint32_t>(meshopt_decoded(triangles, indices.size(), 4, MeshoptView::Mode::Triangles,
                                                       MeshoptView::Filter::None))),
              turned(std::vector<std::uint32_t>(indices.begin(), indices.end())));
    EXPECT_EQ(turned(as<std::uint16_t>(meshopt_decoded(triangles, indices.size(), 2, MeshoptView::Mode::Triangles,
                                                       MeshoptView::Filter::None))),
              turned(shorts));
    EXPECT_EQ(as<std::uint32_t>(meshopt_decoded(sequence, indices.size(), 4, MeshoptView::Mode::Indices,
                                                MeshoptView::Filter::None)),
              std::vector<std::uint32_t>(indices.begin(), indices.end()));
    EXPECT_EQ(as<std::uint16_t>(meshopt_decoded(sequence, indices.size(), 2, MeshoptView::Mode::Indices,
                                                MeshoptView::Filter::None)),
              shorts);
}

// Unit vectors, each (x, y, z, 0), spread over the sphere.
std::vector<float> unit_vectors() {
    std::vector<float> out;
    for (std::size_t i = 0; i < kElements; ++i) {
        const double z = 1.0 - 2.0 * (double(i) + 0.5) / kElements, r = std::sqrt(1.0 - z * z), phi = 2.399963 * double(i);
        out.insert(out.end(), {float(r * std::cos(phi)), float(r * std::sin(phi)), float(z), 0.0f});
    }
    return out;
}

// The filters are held to the decoding the extension specifies (Appendix B), in
// 32-bit floats, written out here from its pseudocode; results may differ from it
// by one in the last place of the decoded integers, as the extension allows. The
// filtered inputs come from libmeshoptimizer's encoders.

// Octahedral: K-bit X and Y, and 1.0 in K bits, to a unit vector in N-bit
// normalized integers.
template <typename Int>
std::array<double, 3> octahedral(const Int* in) {
    const float one = float(in[2]);
    float x = float(in[0]) / one, y = float(in[1]) / one;
    const float z = 1.0f - std::abs(x) - std::abs(y);
    const float t = std::min(z, 0.0f);
    x -= std::copysign(t, x);
    y -= std::copysign(t, y);
    const float len = std::sqrt(x * x + y * y + z * z);
    const float max = float(std::numeric_limits<Int>::max());
    return {std::round(x / len * max), std::round(y / len * max), std::round(z / len * max)};
}

TEST(Meshopt, TheOctahedralFilterDecodesAsSpecified) {
    const std::vector<float> vectors = unit_vectors();
    for (const auto& [stride, bits] : {std::pair<std::size_t, int>{4, 8}, {4, 6}, {8, 16}, {8, 12}}) {
        std::vector<unsigned char> filtered(kElements * stride);
        meshopt_encodeFilterOct(filtered.data(), kElements, stride, bits, vectors.data());
        const auto decoded = meshopt_decoded(encode_vertices(filtered, stride), kElements, stride,
                                             MeshoptView::Mode::Attributes, MeshoptView::Filter::Octahedral);
        for (std::size_t i = 0; i < kElements; ++i) {
            const std::array<double, 3> expected =
                stride == 4 ? octahedral(reinterpret_cast<const std::int8_t*>(filtered.data()) + i * 4)
                            : octahedral(as<std::int16_t>(filtered).data() + i * 4);
            for (std::size_t k = 0; k < 3; ++k) {
                const double got = stride == 4 ? double(std::int8_t(decoded[i * 4 + k]))
                                               : double(as<std::int16_t>(decoded)[i * 4 + k]);
                EXPECT_NEAR(got, expected[k], 1.0) << stride << " bytes, " << bits << " bits, element " << i;
            }
            // The fourth component passes through.
            EXPECT_EQ(decoded[i * stride + stride - 1], filtered[i * stride + stride - 1]);
        }
    }
}

// Quaternion: three K-bit components scaled by sqrt 2, the fourth (the largest,
// positive) rebuilt; the bottom two bits of the fourth input say which it is.
std::array<double, 4> quaternion(const std::int16_t* in) {
    const float range = 1.0f / std::sqrt(2.0f);
    const float one = float(in[3] | 3);
    const float x = float(in[0]) / one * range, y = float(in[1]) / one * range, z = float(in[2]) / one * range;
    const float w = std::sqrt(std::max(0.0f, 1.0f - x * x - y * y - z * z));
    const int largest = in[3] & 3;
    std::array<double, 4> out{};
    out[std::size_t(largest + 1) % 4] = std::round(x * 32767.0f);
    out[std::size_t(largest + 2) % 4] = std::round(y * 32767.0f);
    out[std::size_t(largest + 3) % 4] = std::round(z * 32767.0f);
    out[std::size_t(largest) % 4] = std::round(w * 32767.0f);
    return out;
}

TEST(Meshopt, TheQuaternionFilterDecodesAsSpecified) {
    std::vector<float> quaternions;
    for (std::size_t i = 0; i < kElements; ++i) {  // unit, each of the four components the largest in turn
        const double a = 0.37 * double(i), b = 0.11 * double(i) + 0.2;
        std::array<double, 4> q = {std::cos(a) * std::sin(b), std::sin(a) * std::sin(b), 0.3 * std::cos(b),
                                   std::cos(b)};
        std::rotate(q.begin(), q.begin() + long(i % 4), q.end());
        double len = 0.0;
        for (double c : q) len += c * c;
        for (double c : q) quaternions.push_back(float(c / std::sqrt(len)));
    }
    for (const int bits : {16, 12, 4}) {
        std::vector<unsigned char> filtered(kElements * 8);
        meshopt_encodeFilterQuat(filtered.data(), kElements, 8, bits, quaternions.data());
        const auto decoded = as<std::int16_t>(meshopt_decoded(encode_vertices(filtered, 8), kElements, 8,
                                                              MeshoptView::Mode::Attributes,
                                                              MeshoptView::Filter::Quaternion));
        const auto input = as<std::int16_t>(filtered);
        for (std::size_t i = 0; i < kElements; ++i) {
            const std::array<double, 4> expected = quaternion(input.data() + i * 4);
            for (std::size_t k = 0; k < 4; ++k) {
                EXPECT_NEAR(decoded[i * 4 + k], expected[k], 1.0) << bits << " bits, element " << i;
            }
        }
    }
}

// Exponential: each 32-bit input a signed 8-bit exponent e over a signed 24-bit
// mantissa m, decoded to m 2^e; exact in a float.
TEST(Meshopt, TheExponentialFilterDecodesAsSpecified) {
    std::vector<float> values;
    for (std::size_t i = 0; i < kElements * 3; ++i) values.push_back(float((double(i) - 50.0) * 0.7312));
    for (const int bits : {24, 15, 3}) {
        std::vector<unsigned char> filtered(values.size() * 4);
        meshopt_encodeFilterExp(filtered.data(), kElements, 12, bits, values.data());
        const auto decoded = as<float>(meshopt_decoded(encode_vertices(filtered, 12), kElements, 12,
                                                       MeshoptView::Mode::Attributes, MeshoptView::Filter::Exponential));
        const auto input = as<std::int32_t>(filtered);
        for (std::size_t i = 0; i < input.size(); ++i) {
            const std::int32_t e = input[i] >> 24;
            const std::int32_t m = std::int32_t(std::uint32_t(input[i]) << 8) >> 8;
            EXPECT_EQ(decoded[i], float(std::ldexp(double(m), e))) << bits << " bits, value " << i;
        }
    }
}

// The still life as gltfpack -cc wrote it: its positions in bufferViews[0], its
// indices (TRIANGLES) in bufferViews[2].
const char* const kMeshoptPositions = "bufferViews[0].extensions.EXT_meshopt_compression";

TEST(Meshopt, DamagedStreamsAreNamed) {
    const fs::path truncated = edited(variant("still_life_meshopt.glb"), "meshopt_truncated", [](Glb& g) {
        auto& length = g.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"];
        length = length.get<std::size_t>() - 40;
    });
    test::expect_error_message(test::load_error_of(truncated), truncated.string() + ": " + kMeshoptPositions + ": ",
                               {"the compressed data cannot be decoded (libmeshoptimizer's error"});
    const fs::path header = edited(variant("still_life_meshopt.glb"), "meshopt_header", [](Glb& g) {
        g.bin[g.json["bufferViews"][2]["extensions"]["EXT_meshopt_compression"].value("byteOffset", std::size_t(0))] = 0;
    });
    test::expect_error_message(test::load_error_of(header),
                               header.string() + ": bufferViews[2].extensions.EXT_meshopt_compression: ",
                               {"the compressed data cannot be decoded"});
    const fs::path beyond = edited(variant("still_life_meshopt.glb"), "meshopt_beyond", [](Glb& g) {
        g.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteOffset"] = 1 << 20;
    });
    test::expect_error_message(test::load_error_of(beyond), beyond.string() + ": " + kMeshoptPositions + ": ",
                               {"bytes 1048576 to", "lie beyond buffers[0], which holds"});
}

TEST(Meshopt, LayoutsTheExtensionForbidsAreNamed) {
    using Edit = std::function<void(nlohmann::json&)>;
    const auto refusal = [](const std::string& name, const Edit& edit) {
        const fs::path file = edited(variant("still_life_meshopt.glb"), "meshopt_" + name,
                                     [&](Glb& g) { edit(g.json["bufferViews"][0]); });
        return test::load_error_of(file);
    };
    const auto ext = [](nlohmann::json& view) -> nlohmann::json& { return view["extensions"]["EXT_meshopt_compression"]; };
    test::expect_error_message(refusal("mode", [&](nlohmann::json& v) { ext(v)["mode"] = "VERTICES"; }), "",
                               {kMeshoptPositions, ".mode: expected ATTRIBUTES, TRIANGLES or INDICES, got \"VERTICES\""});
    test::expect_error_message(refusal("filter", [&](nlohmann::json& v) { ext(v)["filter"] = "LOG"; }), "",
                               {kMeshoptPositions, ".filter: expected NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL"});
    test::expect_error_message(refusal("stride", [&](nlohmann::json& v) {
                                   ext(v)["byteStride"] = 6;
                                   v["byteStride"] = 6;
                               }),
                               "", {kMeshoptPositions, ".byteStride: ATTRIBUTES take a multiple of 4 from 4 to 256, got 6"});
    test::expect_error_message(refusal("quaternion", [&](nlohmann::json& v) {
                                   ext(v)["filter"] = "QUATERNION";
                                   ext(v)["byteStride"] = 4;
                                   v["byteStride"] = 4;
                               }),
                               "", {kMeshoptPositions, ".byteStride: QUATERNION takes 8, got 4"});
    test::expect_error_message(refusal("length", [&](nlohmann::json& v) { v["byteLength"] = 4; }), "",
                               {kMeshoptPositions, ": 514 elements of 8 bytes do not fill the bufferView's byteLength 4"});
    test::expect_error_message(refusal("count", [&](nlohmann::json& v) {
                                   ext(v)["count"] = 1 << 24;
                                   v["byteLength"] = 8 << 24;
                               }),
                               "", {kMeshoptPositions, "bytes cannot decode to 16777216 elements of 8 bytes"});
    test::expect_error_message(refusal("buffer", [&](nlohmann::json& v) { ext(v)["buffer"] = 1; }), "",
                               {kMeshoptPositions, ".buffer: buffers[1] is a fallback buffer, which holds no data"});
    test::expect_error_message(refusal("no_count", [&](nlohmann::json& v) { ext(v).erase("count"); }), "",
                               {kMeshoptPositions, ": no count"});
}

// A buffer without data that compressed views refer to is a fallback buffer,
// marked so or not.
TEST(Meshopt, AnUnmarkedBufferWithoutDataIsAFallbackToo) {
    const fs::path file = edited(variant("still_life_meshopt.glb"), "meshopt_unmarked", [](Glb& g) {
        g.json["buffers"][1]["extensions"]["EXT_meshopt_compression"]["fallback"] = "not a boolean";
    });
    EXPECT_EQ(vkrt::load_scene(file).triangles.size(), vkrt::load_scene(variant("still_life_meshopt.glb")).triangles.size());
}

// EXT_meshopt_compression only used, the uncompressed data in a fallback file
// beside the .glb: the compressed data is read, and the fallback file need not be
// there.
TEST(Meshopt, AFallbackBufferIsNotRead) {
    const fs::path dir = test::temp_dir("gltf_compression_fallback");
    fs::copy_file(variant("still_life_meshopt_fallback.glb"), dir / "alone.glb");
    const Scene alone = vkrt::load_scene(dir / "alone.glb");
    const Scene beside = vkrt::load_scene(variant("still_life_meshopt_fallback.glb"));
    ASSERT_EQ(alone.triangles.size(), beside.triangles.size());
    for (std::size_t i = 0; i < alone.triangles.size(); ++i) {
        EXPECT_EQ(alone.triangles[i].vertices, beside.triangles[i].vertices) << i;
    }
    const Glb g = read_glb(variant("still_life_meshopt_fallback.glb"));
    EXPECT_EQ(g.json["extensionsRequired"], nlohmann::json({"KHR_mesh_quantization"})) << "meshopt only used";
}


// ------------------------------------------------------------------ KHR_mesh_quantization

// An octahedron of radius 4 as SHORT positions (8-byte stride), scaled by its
// node to radius 1; BYTE normals of 127 (normalized: 1), UNSIGNED_BYTE texture
// coordinates 0, 1 or 2 (plain), UNSIGNED_SHORT indices. `used` and `accessors`
// fill in what a test varies.
fs::path quantized_octahedron(const std::string& name, const std::string& used, const std::string& normal_accessor,
                              const std::string& position_type = "5122") {
    const int corners[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const std::uint16_t indices[24] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    std::string bin(144, '\0');
    for (int v = 0; v < 6; ++v) {
        for (int k = 0; k < 3; ++k) {
            const auto p = static_cast<std::int16_t>(4 * corners[v][k]);
            std::memcpy(bin.data() + v * 8 + k * 2, &p, 2);
            bin[std::size_t(48 + v * 4 + k)] = static_cast<char>(127 * corners[v][k]);
        }
        bin[std::size_t(72 + v * 4)] = static_cast<char>(v % 3);
        bin[std::size_t(72 + v * 4 + 1)] = static_cast<char>(2 - v % 3);
    }
    std::memcpy(bin.data() + 96, indices, 48);
    const std::string json = R"({"asset": {"version": "2.0"}, )" + used + R"(
      "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "scale": [0.25, 0.25, 0.25]}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3}]}],
      "buffers": [{"byteLength": 144, "uri": "octahedron.bin"}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48, "byteStride": 8},
                      {"buffer": 0, "byteOffset": 48, "byteLength": 24, "byteStride": 4},
                      {"buffer": 0, "byteOffset": 72, "byteLength": 24, "byteStride": 4},
                      {"buffer": 0, "byteOffset": 96, "byteLength": 48}],
      "accessors": [{"bufferView": 0, "componentType": )" + position_type + R"(, "count": 6, "type": "VEC3", "min": [-4, -4, -4], "max": [4, 4, 4]},
                    )" + normal_accessor + R"(,
                    {"bufferView": 2, "componentType": 5121, "count": 6, "type": "VEC2"},
                    {"bufferView": 3, "componentType": 5123, "count": 24, "type": "SCALAR"}]})";
    const fs::path dir = test::temp_dir("gltf_compression_quantized_" + name);
    std::ofstream(dir / "octahedron.bin", std::ios::binary) << bin;
    std::ofstream(dir / (name + ".gltf")) << json;
    return dir / (name + ".gltf");
}

const std::string kUsesQuantization =
    R"("extensionsUsed": ["KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"],)";
const std::string kByteNormals = R"({"bufferView": 1, "componentType": 5120, "normalized": true, "count": 6, "type": "VEC3"})";

TEST(Quantization, PlainIntegersAreTheirValues) {
    const Scene s = vkrt::load_scene(quantized_octahedron("plain", kUsesQuantization, kByteNormals));
    ASSERT_EQ(s.triangles.size(), 8u);
    const Triangle& t = s.triangles[0];  // corners 0, 2, 4
    EXPECT_EQ(t.vertices[0], dvec3(1, 0, 0));
    EXPECT_EQ(t.vertices[1], dvec3(0, 1, 0));
    EXPECT_EQ(t.vertices[2], dvec3(0, 0, 1));
    ASSERT_TRUE(t.normals && t.uvs);
    EXPECT_EQ(glm::normalize((*t.normals)[1]), dvec3(0, 1, 0));
    EXPECT_EQ((*t.uvs)[0], dvec2(0, 2));
    EXPECT_EQ((*t.uvs)[1], dvec2(2, 0));
    EXPECT_EQ((*t.uvs)[2], dvec2(1, 1));
}

TEST(Quantization, PlainIntegersWithoutTheExtensionAreRefused) {
    const fs::path file = quantized_octahedron("unused", "", kByteNormals);
    EXPECT_EQ(test::load_error_of(file),
              file.string() + ": meshes[0].primitives[0].attributes.POSITION: accessors[0] holds SHORT values that are "
                              "not normalized; expected FLOAT or normalized integers (KHR_mesh_quantization allows plain "
                              "ones, but the file does not use it)");
}

// The extension allows plain integers for positions and texture coordinates, not
// for normals; and glTF normalizes bytes and shorts alone.
TEST(Quantization, WhatTheExtensionDoesNotAllowIsRefused) {
    const fs::path normals = quantized_octahedron(
        "plain_normals", kUsesQuantization, R"({"bufferView": 1, "componentType": 5120, "count": 6, "type": "VEC3"})");
    EXPECT_EQ(test::load_error_of(normals),
              normals.string() + ": meshes[0].primitives[0].attributes.NORMAL: accessors[1] holds BYTE values that are "
                                 "not normalized; expected FLOAT or normalized integers");
    const fs::path ints = quantized_octahedron(
        "int_normals", kUsesQuantization,
        R"({"bufferView": 3, "componentType": 5125, "normalized": true, "count": 2, "type": "VEC3"})");
    EXPECT_EQ(test::load_error_of(ints),
              ints.string() + ": meshes[0].primitives[0].attributes.NORMAL: accessors[1] holds normalized UNSIGNED_INT "
                              "values; glTF normalizes bytes and shorts only");
}

}  // namespace
