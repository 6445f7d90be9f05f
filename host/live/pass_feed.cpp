#include "live/pass_feed.hpp"

#include <memory>

#include "image/error_metrics.hpp"

namespace vkrt::live {

void feed_pass(LiveFeed& feed, const PassView& view, const PassLabels& labels) {
    LiveStatus status;
    status.label = labels.label;
    status.samples = view.samples;
    status.target = labels.open_ended ? 0 : view.target;
    status.passes = view.passes;
    status.elapsed = view.elapsed;
    status.seconds_left = view.seconds_left;
    status.rays = total_rays(view.total);
    status.rays_per_second = view.total.render_seconds > 0.0 ? double(status.rays) / view.total.render_seconds : 0.0;
    const bool watched = feed.watched();
    std::shared_ptr<const Image> image;
    if (watched || labels.reference) {
        image = std::make_shared<const Image>(resolve_image(view.total, view.corners));
    }
    if (labels.reference) {
        feed.add_error_point(labels.curve, view.elapsed, error_metrics(*image, *labels.reference).rmse);
    }
    feed.publish(status, watched ? image : nullptr);
}

void feed_outcome(LiveFeed& feed, const RenderOutcome& outcome, const std::string& label) {
    const RenderStats& s = outcome.stats;
    LiveStatus status = feed.status();  // keeps the target the render had
    status.label = label;
    status.samples = s.samples_per_pixel;
    status.passes = s.passes;
    status.elapsed = s.pass_seconds;
    status.seconds_left = 0.0;
    status.rays = s.rays();
    status.rays_per_second = s.render_seconds > 0.0 ? double(s.rays()) / s.render_seconds : 0.0;
    // The last pass's image, when the page has it already, is this one: not sent twice.
    const bool shown = feed.image_samples() == s.samples_per_pixel;
    feed.publish(status, shown ? nullptr : std::make_shared<const Image>(outcome.image));
}

}  // namespace vkrt::live
