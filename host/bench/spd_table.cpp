#include "bench/spd_table.hpp"

#include "bench/support.hpp"

#include <array>
#include <cmath>
#include <utility>

#include <fmt/format.h>

namespace vkrt::bench {
namespace {

constexpr const char* kNone = "–";

// The kinds in table order, each with vkrt's count and the published one.
std::array<std::pair<const char*, std::uint64_t SpdCounts::*>, 4> kinds() {
    return {{{"eye hits", &SpdCounts::eye_hits},
             {"reflection", &SpdCounts::reflection},
             {"refraction", &SpdCounts::refraction},
             {"shadow", &SpdCounts::shadow}}};
}

// 1234567 -> "1,234,567", as the published table writes its counts.
std::string grouped(std::uint64_t n) {
    const std::string digits = std::to_string(n);
    std::string text;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) text += ',';
        text += digits[i];
    }
    return text;
}

std::string difference_text(std::uint64_t got, std::uint64_t published) {
    const std::optional<double> d = difference_percent(got, published);
    if (!d) return "+∞";
    // Rounded to 0.1% the sign of a tiny difference would read as noise; keep it
    // only where the rounded value is not zero.
    const double rounded = std::round(*d * 10.0) / 10.0;
    return rounded == 0.0 ? "0.0%" : fmt::format("{:+.1f}%", rounded);
}

std::string within_text(const SpdRow& r) {
    if (!r.published) return kNone;
    const std::vector<std::string> outside = r.kinds_outside_10_percent();
    if (outside.empty()) return "yes";
    std::string text = "no:";
    for (std::size_t i = 0; i < outside.size(); ++i) text += (i == 0 ? " " : ", ") + outside[i];
    return text;
}

}  // namespace

std::uint64_t SpdRow::rays() const {
    return eye_rays + counts.reflection + counts.refraction + counts.shadow;
}

double SpdRow::mrays_per_second() const {
    return render_seconds > 0.0 ? double(rays()) / render_seconds * 1e-6 : 0.0;
}

std::vector<std::string> SpdRow::kinds_outside_10_percent() const {
    std::vector<std::string> outside;
    if (!published) return outside;
    for (const auto& [name, field] : kinds()) {
        const std::optional<double> d = difference_percent(counts.*field, (*published).*field);
        if (!d || std::fabs(*d) > 10.0) outside.emplace_back(name);
    }
    return outside;
}

std::optional<double> difference_percent(std::uint64_t got, std::uint64_t published) {
    if (published == 0) return got == 0 ? std::optional<double>(0.0) : std::nullopt;
    return 100.0 * (double(got) - double(published)) / double(published);
}

void write_spd_markdown(std::ostream& out, const std::vector<SpdRow>& rows) {
    out << "| scene | primitives | backend ";
    for (const auto& [name, field] : kinds()) out << fmt::format("| {} | published | diff ", name);
    out << "| within 10% | preprocess s | ray-trace s | Mrays/s |\n|---|---:|---";
    for (std::size_t i = 0; i < kinds().size(); ++i) out << "|---:|---:|---:";
    out << "|---|---:|---:|---:|\n";
    for (const SpdRow& r : rows) {
        out << fmt::format("| {} | {} | {} ", r.scene, grouped(r.primitives), r.backend);
        for (const auto& [name, field] : kinds()) {
            const std::uint64_t got = r.counts.*field;
            if (r.published) {
                const std::uint64_t published = (*r.published).*field;
                out << fmt::format("| {} | {} | {} ", grouped(got), grouped(published),
                                   difference_text(got, published));
            } else {
                out << fmt::format("| {} | {} | {} ", grouped(got), kNone, kNone);
            }
        }
        out << fmt::format("| {} | {} | {} | {} |\n", within_text(r), significant(r.preprocess_seconds),
                           significant(r.render_seconds), significant(r.mrays_per_second()));
    }
}

void write_spd_csv(std::ostream& out, const std::vector<SpdRow>& rows) {
    out << "scene,primitives,backend,width,height,eye_rays";
    for (const char* kind : {"eye_hits", "reflection_rays", "refraction_rays", "shadow_rays"}) {
        out << fmt::format(",{0},{0}_published,{0}_diff_pct", kind);
    }
    out << ",within_10pct,dropped_rays,truncated_samples,counts_identical,load_s,flatten_s,grid_build_s,setup_s,"
           "preprocess_s,render_s,rays,mrays_per_s\n";
    for (const SpdRow& r : rows) {
        out << fmt::format("{},{},{},{},{},{}", r.scene, r.primitives, r.backend, r.width, r.height, r.eye_rays);
        for (const auto& [name, field] : kinds()) {
            const std::uint64_t got = r.counts.*field;
            if (!r.published) {
                out << fmt::format(",{},,", got);
                continue;
            }
            const std::uint64_t published = (*r.published).*field;
            const std::optional<double> d = difference_percent(got, published);
            out << fmt::format(",{},{},{}", got, published, d ? fmt::format("{}", *d) : std::string());
        }
        const std::string within = !r.published ? "" : r.kinds_outside_10_percent().empty() ? "yes" : "no";
        out << fmt::format(",{},{},{},{},{},{},{},{},{},{},{},{}\n", within, r.dropped_rays, r.truncated_samples,
                           r.counts_identical ? "yes" : "no", r.load_seconds, r.flatten_seconds,
                           r.grid_build_seconds, r.setup_seconds, r.preprocess_seconds, r.render_seconds, r.rays(),
                           r.mrays_per_second());
    }
}

}  // namespace vkrt::bench
