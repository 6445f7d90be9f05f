// Writes a glTF asset shaped like the scanned PBR helmets users try first: about
// 15,000 triangles and five 2048 x 2048 JPEG textures (base colour, metallic-
// roughness, normal, occlusion, and an emission texture that is black but for a
// few small lamps), as a .gltf with its .bin and images beside it, no camera and no
// light. The build writes it (tests/CMakeLists.txt) so that the repo holds a few
// kilobytes of code instead of megabytes of images; tests and scripts/measure-gltf-
// assets render it.
//
//   make_helmet_like OUT_DIR [SIDE]     writes OUT_DIR/helmet_like.gltf and its files
//
// The textures are procedural (value noise, panel seams, lamps) so that they
// compress as scanned textures do, not as flat colours; the geometry is a UV sphere
// squashed into a shell, whose pole rows hold the degenerate triangles real
// exporters leave in.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "image/image_files.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

// Smooth value noise in [0, 1] at (x, y), lattice hashed (no state, same everywhere).
double lattice(int x, int y, std::uint32_t seed) {
    std::uint32_t h = std::uint32_t(x) * 0x8da6b343u ^ std::uint32_t(y) * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return double(h & 0xffffffu) / double(0xffffff);
}

double value_noise(double x, double y, std::uint32_t seed) {
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    const double sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
    const double a = lattice(x0, y0, seed), b = lattice(x0 + 1, y0, seed);
    const double c = lattice(x0, y0 + 1, seed), d = lattice(x0 + 1, y0 + 1, seed);
    return (a + (b - a) * sx) * (1 - sy) + (c + (d - c) * sx) * sy;
}

// Four octaves, in [0, 1].
double fbm(double x, double y, std::uint32_t seed) {
    double sum = 0.0, amplitude = 0.5;
    for (int o = 0; o < 4; ++o) {
        sum += amplitude * value_noise(x, y, seed + std::uint32_t(o));
        x *= 2.0;
        y *= 2.0;
        amplitude *= 0.5;
    }
    return sum / 0.9375;
}

std::uint8_t byte(double v) { return std::uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

// Panel seams: a grid of grooves, 0 in a groove and 1 on a panel.
double panel(double u, double v) {
    const auto groove = [](double t, double n) {
        const double f = t * n - std::floor(t * n);
        return std::min(1.0, std::min(f, 1.0 - f) * 40.0);
    };
    return std::min(groove(u, 12.0), groove(v, 8.0));
}

// The lamps: a few small discs of the emission texture, about 1% of its area.
double lamp(double u, double v) {
    const double centres[4][2] = {{0.23, 0.41}, {0.27, 0.41}, {0.71, 0.55}, {0.52, 0.31}};
    for (const auto& c : centres) {
        const double du = u - c[0], dv = v - c[1];
        if (du * du + dv * dv < 0.012 * 0.012) return 1.0;
    }
    return 0.0;
}

void write_jpeg(const std::filesystem::path& file, std::uint32_t side, const std::vector<std::uint8_t>& rgb) {
    vkrt::FileSpec spec;
    spec.width = side;
    spec.height = side;
    spec.channels = {"R", "G", "B"};
    spec.types = {vkrt::ChannelType::UInt8, vkrt::ChannelType::UInt8, vkrt::ChannelType::UInt8};
    spec.ints["CompressionQuality"] = 90;
    std::string error;
    if (!vkrt::image_files().write(file.string(), spec, rgb.data(), error)) {
        std::fprintf(stderr, "make_helmet_like: %s: %s\n", file.c_str(), error.c_str());
        std::exit(1);
    }
}

// Texture `kind` (0 colour, 1 metallic-roughness, 2 normal, 3 occlusion, 4 emission).
std::vector<std::uint8_t> texture(int kind, std::uint32_t side) {
    std::vector<std::uint8_t> rgb(std::size_t(side) * side * 3);
    for (std::uint32_t y = 0; y < side; ++y) {
        for (std::uint32_t x = 0; x < side; ++x) {
            const double u = (x + 0.5) / side, v = (y + 0.5) / side;
            const double grime = fbm(u * 64.0, v * 64.0, 7);
            const double p = panel(u, v);
            std::uint8_t* o = &rgb[(std::size_t(y) * side + x) * 3];
            switch (kind) {
            case 0:  // worn paint over grey metal
                o[0] = byte((0.55 + 0.25 * grime) * p);
                o[1] = byte((0.50 + 0.2 * grime) * p);
                o[2] = byte((0.40 + 0.15 * grime) * p);
                break;
            case 1:  // glTF packing: green roughness, blue metallic
                o[0] = 0;
                o[1] = byte(0.25 + 0.6 * grime);
                o[2] = byte(grime > 0.55 ? 1.0 : 0.0);
                break;
            case 2: {  // a height field of panels and grime, as tangent-space normals
                const double h = 1.0 / side;
                const auto height = [&](double a, double b) { return 0.6 * panel(a, b) + 0.1 * fbm(a * 64.0, b * 64.0, 7); };
                const double dx = (height(u + h, v) - height(u - h, v)) / (2.0 * h) * 0.002;
                const double dy = (height(u, v + h) - height(u, v - h)) / (2.0 * h) * 0.002;
                const double len = std::sqrt(dx * dx + dy * dy + 1.0);
                o[0] = byte(0.5 - 0.5 * dx / len);
                o[1] = byte(0.5 + 0.5 * dy / len);
                o[2] = byte(0.5 + 0.5 / len);
                break;
            }
            case 3: o[0] = o[1] = o[2] = byte(0.4 + 0.6 * p * (0.7 + 0.3 * grime)); break;
            default: {
                const double e = lamp(u, v);
                o[0] = byte(e);
                o[1] = byte(0.8 * e);
                o[2] = byte(0.5 * e);
                break;
            }
            }
        }
    }
    return rgb;
}

struct Mesh {
    std::vector<float> positions, normals, uvs;
    std::vector<std::uint16_t> indices;
};

// A UV sphere of `rings` x `segments` quads, squashed and hollowed at the bottom into
// a shell. Each pole row keeps its quads, one of whose triangles has zero area.
Mesh shell(int rings, int segments) {
    Mesh m;
    for (int r = 0; r <= rings; ++r) {
        const double theta = kPi * r / rings * 0.8;  // stops short of the bottom pole: an open shell
        for (int s = 0; s <= segments; ++s) {
            const double phi = 2.0 * kPi * s / segments;
            const double nx = std::sin(theta) * std::cos(phi), ny = std::cos(theta), nz = std::sin(theta) * std::sin(phi);
            m.positions.insert(m.positions.end(), {float(0.9 * nx), float(1.0 * ny), float(1.05 * nz)});
            m.normals.insert(m.normals.end(), {float(nx), float(ny), float(nz)});
            m.uvs.insert(m.uvs.end(), {float(double(s) / segments), float(double(r) / rings)});
        }
    }
    const int row = segments + 1;
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            const auto a = std::uint16_t(r * row + s), b = std::uint16_t(a + 1);
            const auto c = std::uint16_t(a + row), d = std::uint16_t(c + 1);
            m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
        }
    }
    return m;
}

template <class T>
void append(std::vector<std::uint8_t>& bin, const std::vector<T>& v) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(v.data());
    bin.insert(bin.end(), p, p + v.size() * sizeof(T));
    while (bin.size() % 4 != 0) bin.push_back(0);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || argc > 3) {
        std::fprintf(stderr, "usage: make_helmet_like OUT_DIR [SIDE]\n");
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    const std::uint32_t side = argc == 3 ? std::uint32_t(std::stoul(argv[2])) : 2048u;
    std::filesystem::create_directories(dir);

    const Mesh m = shell(88, 88);  // 15,488 triangles
    std::vector<std::uint8_t> bin;
    append(bin, m.positions);
    const std::size_t normals_at = bin.size();
    append(bin, m.normals);
    const std::size_t uvs_at = bin.size();
    append(bin, m.uvs);
    const std::size_t indices_at = bin.size();
    append(bin, m.indices);
    std::ofstream(dir / "helmet_like.bin", std::ios::binary).write(reinterpret_cast<const char*>(bin.data()),
                                                                    std::streamsize(bin.size()));

    const char* names[5] = {"albedo.jpg", "metal_roughness.jpg", "normal.jpg", "occlusion.jpg", "emissive.jpg"};
    for (int k = 0; k < 5; ++k) write_jpeg(dir / names[k], side, texture(k, side));

    using nlohmann::json;
    const std::size_t vertices = m.positions.size() / 3;
    std::array<float, 3> lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};  // glTF requires POSITION's bounds
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], m.positions[i]);
        hi[i % 3] = std::max(hi[i % 3], m.positions[i]);
    }
    json views = json::array();
    const auto view = [&](std::size_t offset, std::size_t length, int target) {
        views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}, {"target", target}});
    };
    view(0, vertices * 12, 34962);
    view(normals_at, vertices * 12, 34962);
    view(uvs_at, vertices * 8, 34962);
    view(indices_at, m.indices.size() * 2, 34963);
    json images = json::array(), textures = json::array();
    for (int k = 0; k < 5; ++k) {
        images.push_back({{"uri", names[k]}});
        textures.push_back({{"sampler", 0}, {"source", k}});
    }
    const json gltf = {
        {"asset", {{"version", "2.0"}, {"generator", "vkrt tests/assets/make_helmet_like.cpp"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"name", "helmet"}, {"mesh", 0}, {"rotation", {0.0, 0.3826834, 0.0, 0.9238795}}}}},
        {"meshes",
         {{{"primitives",
            {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}, {"material", 0}}}}}}},
        {"materials",
         {{{"name", "helmet"},
           {"pbrMetallicRoughness",
            {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 1}}}}},
           {"normalTexture", {{"index", 2}}},
           {"occlusionTexture", {{"index", 3}}},
           {"emissiveTexture", {{"index", 4}}},
           {"emissiveFactor", {1.0, 1.0, 1.0}}}}},
        {"textures", textures},
        {"images", images},
        {"samplers", {{{"magFilter", 9729}, {"minFilter", 9987}}}},
        {"accessors",
         {{{"bufferView", 0}, {"componentType", 5126}, {"count", vertices}, {"type", "VEC3"},
           {"min", lo}, {"max", hi}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", vertices}, {"type", "VEC3"}},
          {{"bufferView", 2}, {"componentType", 5126}, {"count", vertices}, {"type", "VEC2"}},
          {{"bufferView", 3}, {"componentType", 5123}, {"count", m.indices.size()}, {"type", "SCALAR"}}}},
        {"buffers", {{{"uri", "helmet_like.bin"}, {"byteLength", bin.size()}}}},
        {"bufferViews", views},
    };
    std::ofstream(dir / "helmet_like.gltf") << gltf.dump(1) << "\n";
    return 0;
}
