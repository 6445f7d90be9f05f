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
#include "render/fingerprint.hpp"
#include "render/partial_file.hpp"
#include "render/render.hpp"
#include "render/sample_ranges.hpp"
#include "scene/limits.hpp"

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
        if (p.version != first.version) {
            throw std::runtime_error(fmt::format(
                "{} was rendered by vkrt {} but {} by vkrt {}: builds whose kernels differ draw different samples; "
                "render one of them again with the other's build",
                names[i], p.version, names[0], first.version));
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

// The partials' samples against the ones wanted: samples outside it are an error;
// returns those of `wanted` that no partial covers.
std::vector<SampleRange> check_coverage(const std::vector<std::string>& names, const std::vector<PartialFile>& parts,
                                        SampleRange wanted) {
    std::vector<SampleRange> covered;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        for (const SampleRange& r : parts[i].samples) {
            if (r.first < wanted.first || r.end() > wanted.end()) {
                throw std::runtime_error(fmt::format("{} holds samples {}, outside --samples {}", names[i],
                                                     format_sample_range(r), format_sample_range(wanted)));
            }
            covered.push_back(r);
        }
    }
    return missing_samples(wanted, covered);
}

// vkrt merge --missing: what is left to render, one range a line on stdout.
int list_missing(const MergeArgs& args) {
    if (args.samples.empty()) {
        throw std::runtime_error("--missing needs --samples A:B, the samples the finished image is to have");
    }
    const SampleRange wanted = parse_sample_range(args.samples, limits::kMaxSpp);
    std::vector<std::string> names;
    std::vector<PartialFile> parts;
    for (const std::string& name : args.partials) {
        try {
            parts.push_back(check_partial(name));  // the pixels too: a damaged file is missing
            names.push_back(name);
        } catch (const ImageError& e) {
            fmt::print(stderr, "warning: {}; its samples count as missing\n", e.what());
        }
    }
    if (!parts.empty()) check_mergeable(names, parts);
    const std::vector<SampleRange> missing = check_coverage(names, parts, wanted);
    for (const SampleRange& r : split_sample_ranges(missing, args.tasks)) fmt::print("{}\n", format_sample_range(r));
    return 0;
}

}  // namespace

int run_merge(const MergeArgs& args) {
    if (args.missing) return list_missing(args);
    if (args.output.empty()) throw std::runtime_error("--output is required: where to write the merged image");
    if (args.partials.empty()) throw std::runtime_error("no partial files given: nothing to merge");
    app::check_writable_image(args.output);
    // Every header checked before any pixels are read: a mistake is found at once,
    // and only one partial's pixels are in memory at a time.
    std::vector<PartialFile> headers;
    for (const std::string& name : args.partials) headers.push_back(read_partial_header(name));
    check_mergeable(args.partials, headers);
    std::vector<SampleRange> covered;
    for (const PartialFile& p : headers) covered.insert(covered.end(), p.samples.begin(), p.samples.end());
    const std::vector<SampleRange> missing =
        args.samples.empty() ? sample_gaps(covered)
                             : check_coverage(args.partials, headers, parse_sample_range(args.samples, limits::kMaxSpp));
    if (!missing.empty() && !args.allow_gaps) {
        throw std::runtime_error(fmt::format(
            "samples {} are missing: no partial holds them. Render them (`vkrt merge --missing --samples A:B "
            "PARTIAL...` lists them) and merge again, or pass --allow-gaps to average the samples there are",
            format_sample_ranges(missing)));
    }

    PartialFile merged;
    merged.scene = headers.front().scene;
    merged.seed = headers.front().seed;
    merged.fingerprint = headers.front().fingerprint;
    merged.corners = headers.front().corners;
    merged.version = headers.front().version;
    std::set<std::string> backends;
    for (std::size_t i = 0; i < headers.size(); ++i) {
        const PartialFile p = add_partial(args.partials[i], merged.sums);
        merged.samples.insert(merged.samples.end(), p.samples.begin(), p.samples.end());
        backends.insert(p.backend);
    }
    merged.samples = normalize_sample_ranges(merged.samples);
    merged.backend = fmt::format("{}", fmt::join(backends, "+"));

    if (app::is_exr(args.output)) {
        write_partial(merged, args.output);
    } else {
        write_image(resolve_image(merged.sums, merged.corners), args.output, display_with({}, args.display));
    }

    if (!args.quiet) {
        for (std::size_t i = 0; i < headers.size(); ++i) {
            fmt::print("merged    {}: samples {} ({})\n", args.partials[i], format_sample_ranges(headers[i].samples),
                       headers[i].backend);
        }
        fmt::print("image     {}x{}{}, samples {}: {} per pixel\n", merged.sums.width, merged.sums.height,
                   merged.corners ? " corner rays" : "", format_sample_ranges(merged.samples),
                   sample_count(merged.samples));
        fmt::print("wrote     {}{}\n", args.output, app::is_exr(args.output) ? " (a partial file, mergeable again)" : "");
    }
    if (!missing.empty()) {
        fmt::print(stderr,
                   "warning: the partials leave out samples {}; the image is the average of the {} samples per pixel "
                   "that were rendered\n",
                   format_sample_ranges(missing), sample_count(merged.samples));
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
