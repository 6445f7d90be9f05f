#include "render/sample_ranges.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include <fmt/format.h>

namespace vkrt {
namespace {

// A whole number of at most 10 digits (so it cannot overflow 64 bits), or nothing.
std::optional<std::uint64_t> whole(const std::string& text) {
    if (text.empty() || text.size() > 10) return std::nullopt;
    std::uint64_t value = 0;
    for (char c : text) {
        if (c < '0' || c > '9') return std::nullopt;
        value = value * 10 + std::uint64_t(c - '0');
    }
    return value;
}

struct Parsed {
    std::optional<std::uint64_t> first, end;
};

Parsed split_range(const std::string& text) {
    const std::size_t colon = text.find(':');
    if (colon == std::string::npos) return {};
    return {whole(text.substr(0, colon)), whole(text.substr(colon + 1))};
}

}  // namespace

SampleRange parse_sample_range(const std::string& text, std::uint32_t max_end) {
    const Parsed p = split_range(text);
    if (!p.first || !p.end) {
        throw std::invalid_argument(fmt::format(
            "expected A:B, two whole numbers for the samples A to B - 1 (e.g. 0:16), got '{}'", text));
    }
    if (*p.first >= *p.end) {
        throw std::invalid_argument(fmt::format(
            "'{}' is an empty range: the first sample ({}) must be below the end ({})", text, *p.first, *p.end));
    }
    if (*p.end > max_end) {
        throw std::invalid_argument(fmt::format(
            "'{}' ends beyond sample {}: a pixel takes at most {} samples, indices 0 to {}", text, max_end, max_end,
            max_end - 1));
    }
    return {std::uint32_t(*p.first), std::uint32_t(*p.end - *p.first)};
}

std::string format_sample_range(SampleRange range) { return fmt::format("{}:{}", range.first, range.end()); }

std::string format_sample_ranges(const std::vector<SampleRange>& ranges) {
    std::string out;
    for (const SampleRange& r : ranges) {
        if (!out.empty()) out += ',';
        out += format_sample_range(r);
    }
    return out;
}

std::optional<std::vector<SampleRange>> parse_sample_ranges(const std::string& text, std::uint32_t max_end) {
    std::vector<SampleRange> out;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        const Parsed p = split_range(text.substr(start, comma - start));
        if (!p.first || !p.end || *p.first >= *p.end || *p.end > max_end) return std::nullopt;
        out.push_back({std::uint32_t(*p.first), std::uint32_t(*p.end - *p.first)});
        start = comma + 1;
    }
    return out;
}

std::vector<SampleRange> normalize_sample_ranges(std::vector<SampleRange> ranges) {
    std::sort(ranges.begin(), ranges.end(), [](SampleRange a, SampleRange b) { return a.first < b.first; });
    std::vector<SampleRange> out;
    for (const SampleRange& r : ranges) {
        if (!out.empty() && out.back().end() == r.first) {
            out.back().count += r.count;
        } else {
            out.push_back(r);
        }
    }
    return out;
}

std::optional<SampleRange> overlap(SampleRange a, SampleRange b) {
    const std::uint32_t first = std::max(a.first, b.first);
    const std::uint32_t end = std::min(a.end(), b.end());
    if (first >= end) return std::nullopt;
    return SampleRange{first, end - first};
}

std::vector<SampleRange> sample_gaps(const std::vector<SampleRange>& ranges) {
    if (ranges.empty()) return {};
    const std::vector<SampleRange> sorted = normalize_sample_ranges(ranges);
    const std::uint32_t first = sorted.front().first;
    return missing_samples({first, sorted.back().end() - first}, sorted);
}

std::vector<SampleRange> missing_samples(SampleRange wanted, const std::vector<SampleRange>& covered) {
    std::vector<SampleRange> missing;
    std::uint32_t from = wanted.first;
    for (const SampleRange& r : normalize_sample_ranges(covered)) {
        if (r.end() <= from) continue;
        if (r.first >= wanted.end()) break;
        if (r.first > from) missing.push_back({from, r.first - from});
        from = std::max(from, r.end());
    }
    if (from < wanted.end()) missing.push_back({from, wanted.end() - from});
    return missing;
}

std::vector<SampleRange> split_sample_ranges(const std::vector<SampleRange>& ranges, std::uint32_t pieces) {
    const std::uint64_t total = sample_count(ranges);
    if (pieces == 0 || total == 0) return ranges;
    std::vector<SampleRange> out;
    for (const SampleRange& r : ranges) {
        // Pieces in proportion to the range's share of the samples: at least one, at
        // most one per sample.
        const std::uint64_t share = (std::uint64_t(r.count) * pieces + total / 2) / total;
        const std::uint64_t k = std::clamp<std::uint64_t>(share, 1, r.count);
        for (std::uint64_t j = 0; j < k; ++j) {
            const auto a = std::uint32_t(r.first + r.count * j / k);
            const auto b = std::uint32_t(r.first + r.count * (j + 1) / k);
            out.push_back({a, b - a});
        }
    }
    return out;
}

std::uint64_t sample_count(const std::vector<SampleRange>& ranges) {
    std::uint64_t n = 0;
    for (const SampleRange& r : ranges) n += r.count;
    return n;
}

}  // namespace vkrt
