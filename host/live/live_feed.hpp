#pragma once
// What a live preview shows (host/live/live_server.hpp), handed from the render's
// thread to the server's: the newest image, the figures beside it, the error curves,
// and a stop request going the other way. Every member is safe to call from any thread.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace vkrt::live {

// The figures of a render after a pass.
struct LiveStatus {
    std::string label;                 // what is rendering: the scene, or a converge curve
    std::uint32_t samples = 0;         // per pixel, done
    std::uint32_t target = 0;          // per pixel, the most the render will take; 0: until the time is up
    std::uint32_t passes = 0;
    double elapsed = 0.0;              // seconds of passes
    double seconds_left = 0.0;         // estimated
    std::uint64_t rays = 0;
    double rays_per_second = 0.0;      // of the kernel's own time, as the summary counts it
};

class LiveFeed {
public:
    // A page that asked for the status within this long is watching: images are
    // worth resolving for it, and the end of the render waits briefly for it.
    static constexpr double kWatchSeconds = 3.0;

    void set_renderer(std::string backend, std::string device);
    // How the preview shows the linear image, as the render's 8-bit output would.
    void set_display(const Display& display);
    // The newest figures, and with them a new image unless `image` is null.
    void publish(const LiveStatus& status, std::shared_ptr<const Image> image);
    // The samples per pixel of the newest image (0 before the first).
    std::uint32_t image_samples() const;
    LiveStatus status() const;
    // A point of an error curve (RMSE against a reference at a time of passes).
    void add_error_point(const std::string& curve, double seconds, double rmse);
    // The render has ended ("finished", or "stopped" after a stop request) and its
    // output is written.
    void finish(const std::string& output);

    void request_stop();
    bool stop_requested() const;
    bool watched() const;

    // The page's view as JSON; counts as the page watching.
    std::string status_json();
    // The newest image as PNG, encoded once per image; null before the first.
    // `version` is that image's number, which the status names.
    std::shared_ptr<const std::vector<std::uint8_t>> png(std::uint64_t& version);

    // After finish: while a page is watching, waits (at most `seconds`) until it has
    // seen the final status and fetched the newest image, so that it shows the end
    // rather than a lost connection.
    void wait_until_seen(double seconds);

private:
    using Clock = std::chrono::steady_clock;
    bool watched_locked() const;  // watched(), with mutex_ held
    struct Curve {
        std::string name;
        std::vector<std::pair<double, double>> points;
    };

    mutable std::mutex mutex_;
    std::condition_variable seen_;
    std::string backend_, device_;
    Display display_;
    LiveStatus status_;
    std::shared_ptr<const Image> image_;
    std::uint64_t image_version_ = 0;
    std::uint32_t image_samples_ = 0;
    std::uint64_t served_version_ = 0;
    std::shared_ptr<const std::vector<std::uint8_t>> png_;
    std::uint64_t png_version_ = 0;
    std::vector<Curve> curves_;
    std::string state_ = "starting";
    std::string output_;
    bool stop_ = false;
    bool final_seen_ = false;
    Clock::time_point last_poll_{};
    bool polled_ = false;
};

}  // namespace vkrt::live
