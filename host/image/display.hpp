#pragma once
// How linear radiance becomes an 8-bit pixel: an exposure in stops, then a tone
// curve, then the sRGB encoding (image.hpp). Float formats (.exr, .hdr) store the
// linear values and take none of this.
#include <optional>
#include <string_view>

namespace vkrt {

enum class Tonemap {
    None,    // clamp to [0, 1]
    Filmic,  // Narkowicz's fit of the ACES filmic curve: a toe, then a shoulder toward 1
};

struct Display {
    double exposure = 0.0;  // stops: the radiance is scaled by 2^exposure
    Tonemap tonemap = Tonemap::None;
};

// render.tonemap's and --tonemap's names: "none", "filmic". Inline: the scene
// loader reads them without the image library.
inline const char* tonemap_name(Tonemap tonemap) { return tonemap == Tonemap::Filmic ? "filmic" : "none"; }

inline std::optional<Tonemap> parse_tonemap(std::string_view name) {
    if (name == "none") return Tonemap::None;
    if (name == "filmic") return Tonemap::Filmic;
    return std::nullopt;
}

// The display value in [0, 1] of a linear channel value, before the sRGB encoding.
float display_value(float linear, const Display& display);

}  // namespace vkrt
