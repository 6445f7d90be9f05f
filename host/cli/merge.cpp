// vkrt merge: partial files of disjoint sample ranges added up into one image.
#include <algorithm>
#include <filesystem>
#include <set>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli/commands.hpp"
#include "app/output_paths.hpp"
#include "image/image.hpp"
#include "render/accumulate.hpp"
#include "render/fingerprint.hpp"
#include "render/partial_file.hpp"
#include "render/render.hpp"
#include "render/sample_ranges.hpp"

namespace vkrt::cli {
namespace {

std::string describe(const PartialFile& p) {
    return fmt::format("scene '{}', seed {}, fingerprint {}", p.scene, p.seed, format_fingerprint(p.fingerprint));
}

// Everything that would make the sum meaningless is refused before anything is added.
void check_mergeable(const std::vector<std::string>& names, const std::vector<PartialFile>& parts) {
    const PartialFile& first = parts.front();
    for (std::size_t i = 1; i < parts.size(); ++i) {
        const PartialFile& p = parts[i];
        if (p.sums.width != first.sums.width || p.sums.height != first.sums.height) {
            throw std::runtime_error(fmt::format("{} is {}x{} but {} is {}x{}: only partials of one render merge",
                                                 names[i], p.sums.width, p.sums.height, names[0], first.sums.width,
                                                 first.sums.height));
        }
        if (p.fingerprint != first.fingerprint || p.corners != first.corners) {
            throw std::runtime_error(fmt::format(
                "{} ({}) is not a render of the same scene and settings as {} ({}): only partials of one render merge",
                names[i], describe(p), names[0], describe(first)));
        }
    }
    for (std::size_t i = 0; i < parts.size(); ++i) {
        for (std::size_t j = i + 1; j < parts.size(); ++j) {
            std::error_code ec;
            if (std::filesystem::equivalent(names[i], names[j], ec)) {
                throw std::runtime_error(fmt::format("{} is given twice: each sample may be merged once", names[i]));
            }
            for (const SampleRange& a : parts[i].samples) {
                for (const SampleRange& b : parts[j].samples) {
                    if (const auto both = overlap(a, b)) {
                        throw std::runtime_error(fmt::format(
                            "{} (samples {}) and {} (samples {}) overlap in samples {}: each sample may be merged "
                            "once",
                            names[i], format_sample_ranges(parts[i].samples), names[j],
                            format_sample_ranges(parts[j].samples), format_sample_range(*both)));
                    }
                }
            }
        }
    }
}

}  // namespace

int run_merge(const MergeArgs& args) {
    app::check_writable_image(args.output);
    std::vector<PartialFile> parts;
    for (const std::string& name : args.partials) parts.push_back(read_partial(name));
    check_mergeable(args.partials, parts);

    PartialFile merged;
    merged.scene = parts.front().scene;
    merged.seed = parts.front().seed;
    merged.fingerprint = parts.front().fingerprint;
    merged.corners = parts.front().corners;
    std::set<std::string> backends;
    for (const PartialFile& p : parts) {
        accumulate(merged.sums, p.sums);
        merged.samples.insert(merged.samples.end(), p.samples.begin(), p.samples.end());
        backends.insert(p.backend);
    }
    merged.samples = normalize_sample_ranges(merged.samples);
    merged.backend = fmt::format("{}", fmt::join(backends, "+"));

    if (app::is_exr(args.output)) {
        write_partial(merged, args.output);
    } else {
        write_image(resolve_image(merged.sums, merged.corners), args.output);
    }

    if (!args.quiet) {
        for (std::size_t i = 0; i < parts.size(); ++i) {
            fmt::print("merged    {}: samples {} ({})\n", args.partials[i], format_sample_ranges(parts[i].samples),
                       parts[i].backend);
        }
        fmt::print("image     {}x{}{}, samples {}: {} per pixel\n", merged.sums.width, merged.sums.height,
                   merged.corners ? " corner rays" : "", format_sample_ranges(merged.samples),
                   sample_count(merged.samples));
        fmt::print("wrote     {}{}\n", args.output, app::is_exr(args.output) ? " (a partial file, mergeable again)" : "");
    }
    if (const std::vector<SampleRange> gaps = sample_gaps(merged.samples); !gaps.empty()) {
        fmt::print(stderr,
                   "warning: the partials leave out samples {}; the image is the average of the {} samples per pixel "
                   "that were rendered\n",
                   format_sample_ranges(gaps), sample_count(merged.samples));
    }
    if (backends.size() > 1) {
        fmt::print(stderr,
                   "warning: the partials come from different backends ({}): they agree to the cross-check's "
                   "tolerance, not bit for bit\n",
                   fmt::join(backends, ", "));
    }
    return 0;
}

}  // namespace vkrt::cli
