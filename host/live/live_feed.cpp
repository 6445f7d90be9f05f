#include "live/live_feed.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "image/png_encode.hpp"

namespace vkrt::live {

void LiveFeed::set_renderer(std::string backend, std::string device) {
    const std::lock_guard lock(mutex_);
    backend_ = std::move(backend);
    device_ = std::move(device);
}

void LiveFeed::set_display(const Display& display) {
    const std::lock_guard lock(mutex_);
    display_ = display;
}

void LiveFeed::publish(const LiveStatus& status, std::shared_ptr<const Image> image) {
    const std::lock_guard lock(mutex_);
    status_ = status;
    if (state_ == "starting") state_ = "rendering";
    if (image) {
        image_ = std::move(image);
        ++image_version_;
        image_samples_ = status.samples;
    }
}

std::uint32_t LiveFeed::image_samples() const {
    const std::lock_guard lock(mutex_);
    return image_samples_;
}

LiveStatus LiveFeed::status() const {
    const std::lock_guard lock(mutex_);
    return status_;
}

void LiveFeed::add_error_point(const std::string& curve, double seconds, double rmse) {
    const std::lock_guard lock(mutex_);
    if (curves_.empty() || curves_.back().name != curve) curves_.push_back({curve, {}});
    curves_.back().points.emplace_back(seconds, rmse);
}

void LiveFeed::finish(const std::string& output) {
    const std::lock_guard lock(mutex_);
    state_ = stop_ ? "stopped" : "finished";
    output_ = output;
}

void LiveFeed::request_stop() {
    const std::lock_guard lock(mutex_);
    if (state_ == "finished" || state_ == "stopped") return;
    stop_ = true;
    state_ = "stopping";
}

bool LiveFeed::stop_requested() const {
    const std::lock_guard lock(mutex_);
    return stop_;
}

bool LiveFeed::watched_locked() const {
    return polled_ && std::chrono::duration<double>(Clock::now() - last_poll_).count() < kWatchSeconds;
}

bool LiveFeed::watched() const {
    const std::lock_guard lock(mutex_);
    return watched_locked();
}

std::string LiveFeed::status_json() {
    std::unique_lock lock(mutex_);
    polled_ = true;
    last_poll_ = Clock::now();
    nlohmann::json curves = nlohmann::json::array();
    for (const Curve& c : curves_) curves.push_back({{"name", c.name}, {"points", c.points}});
    const nlohmann::json json{
        {"state", state_},
        {"backend", backend_},
        {"device", device_},
        {"label", status_.label},
        {"samples", status_.samples},
        {"target", status_.target},
        {"passes", status_.passes},
        {"elapsed", status_.elapsed},
        {"seconds_left", status_.seconds_left},
        {"rays", status_.rays},
        {"rays_per_second", status_.rays_per_second},
        {"image", image_version_},
        {"curves", curves},
        {"output", output_},
    };
    if (state_ == "finished" || state_ == "stopped") {
        final_seen_ = true;
        lock.unlock();
        seen_.notify_all();
    }
    return json.dump();
}

std::shared_ptr<const std::vector<std::uint8_t>> LiveFeed::png(std::uint64_t& version) {
    std::unique_lock lock(mutex_);
    if (png_version_ == image_version_ || !image_) {
        version = served_version_ = png_version_;
        lock.unlock();
        seen_.notify_all();
        return png_;
    }
    const std::shared_ptr<const Image> image = image_;
    const std::uint64_t wanted = image_version_;
    const Display display = display_;
    lock.unlock();
    // Encoded outside the lock: the render thread publishes meanwhile without waiting.
    auto encoded = std::make_shared<const std::vector<std::uint8_t>>(encode_png(*image, display));
    lock.lock();
    if (wanted > png_version_) {
        png_ = encoded;
        png_version_ = wanted;
    }
    version = wanted;
    served_version_ = std::max(served_version_, wanted);
    lock.unlock();
    seen_.notify_all();
    return encoded;
}

void LiveFeed::wait_until_seen(double seconds) {
    std::unique_lock lock(mutex_);
    if (!watched_locked()) return;
    seen_.wait_for(lock, std::chrono::duration<double>(seconds),
                   [&] { return final_seen_ && served_version_ == image_version_; });
}

}  // namespace vkrt::live
