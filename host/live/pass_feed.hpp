#pragma once
// From a render's pass to its live preview: the figures always, the image (and its
// error against a reference) only while a page is watching, since resolving an
// image every pass costs the render time.
#include <string>

#include "image/image.hpp"
#include "live/live_feed.hpp"
#include "render/render.hpp"

namespace vkrt::live {

struct PassLabels {
    std::string label;            // shown above the image
    std::string curve;            // the error curve's name, when there is a reference
    const Image* reference = nullptr;
    bool open_ended = false;      // a time budget alone ends the render: the sample count is only a cap
};

void feed_pass(LiveFeed& feed, const PassView& view, const PassLabels& labels);

// The finished render: the figures of its own statistics, and its image unless the
// feed holds it already.
void feed_outcome(LiveFeed& feed, const RenderOutcome& outcome, const std::string& label);

}  // namespace vkrt::live
