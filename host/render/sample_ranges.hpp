#pragma once
// Sample ranges as users write them ("A:B", samples A to B - 1) and as partial files
// record them (a list, "0:2,5:8"): parsing, printing, and the checks a merge needs.
#include <optional>
#include <string>
#include <vector>

#include "render/backend.hpp"

namespace vkrt {

// "A:B" with whole numbers A < B <= max_end. Throws std::invalid_argument with a
// one-line message that names the problem (malformed, empty, beyond max_end).
SampleRange parse_sample_range(const std::string& text, std::uint32_t max_end);

// "A:B" for one range, "A:B,C:D" for a list.
std::string format_sample_range(SampleRange range);
std::string format_sample_ranges(const std::vector<SampleRange>& ranges);
// The inverse of format_sample_ranges; empty optional for anything else.
std::optional<std::vector<SampleRange>> parse_sample_ranges(const std::string& text, std::uint32_t max_end);

// Sorted by first sample, with ranges that touch joined: 0:2 and 2:5 become 0:5.
// The ranges must not overlap (see first_overlap).
std::vector<SampleRange> normalize_sample_ranges(std::vector<SampleRange> ranges);

// The samples two ranges share, if any.
std::optional<SampleRange> overlap(SampleRange a, SampleRange b);

// The samples between the first and the last that none of the ranges covers.
std::vector<SampleRange> sample_gaps(const std::vector<SampleRange>& ranges);

// The samples of `wanted` that none of `covered` holds, in order.
std::vector<SampleRange> missing_samples(SampleRange wanted, const std::vector<SampleRange>& covered);

// Each range cut into nearly equal consecutive ranges, about `pieces` in all, in
// proportion to its share of the samples (at least one per range): the work of
// `pieces` machines. 0 leaves the ranges as they are.
std::vector<SampleRange> split_sample_ranges(const std::vector<SampleRange>& ranges, std::uint32_t pieces);

std::uint64_t sample_count(const std::vector<SampleRange>& ranges);

}  // namespace vkrt
