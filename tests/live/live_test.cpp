// The live preview's parts that need no browser: its PNG, its address parsing, the
// feed between the render and the server, stopping a render after a pass, and
// atomic output. The page itself is tested in Chromium (tests/live/).
#include <gtest/gtest.h>

#include <fstream>
#include <stdexcept>

#include "app/output_paths.hpp"
#include "cpu/cpu_backend.hpp"
#include "image/image.hpp"
#include "image/png_encode.hpp"
#include "live/live_feed.hpp"
#include "live/live_server.hpp"
#include "render/render.hpp"
#include "test_support.hpp"

#include <nlohmann/json.hpp>

namespace {

using namespace vkrt;
namespace fs = std::filesystem;

Image gradient(std::uint32_t w, std::uint32_t h) {
    Image image(w, h);
    for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = float(i % 97) / 80.0f - 0.1f;  // beyond [0, 1] too
    return image;
}

TEST(LivePng, HoldsTheBytesOfAPngFile) {
    const fs::path dir = test::temp_dir("live_png");
    const Image image = gradient(37, 11);  // odd sizes: no row padding to hide behind
    const std::vector<std::uint8_t> png = encode_png(image);
    std::ofstream(dir / "memory.png", std::ios::binary).write(reinterpret_cast<const char*>(png.data()),
                                                              std::streamsize(png.size()));
    write_image(image, dir / "file.png");
    const Image from_memory = read_image(dir / "memory.png");
    const Image from_file = read_image(dir / "file.png");
    ASSERT_EQ(from_memory.width, 37u);
    ASSERT_EQ(from_memory.height, 11u);
    EXPECT_EQ(from_memory.rgb, from_file.rgb);
}

TEST(LiveEndpoint, ReadsPortAndAddress) {
    const auto at = [](const std::string& text) {
        const live::Endpoint e = live::parse_endpoint(text);
        return e.address + " " + std::to_string(e.port);
    };
    EXPECT_EQ(at("8080"), "127.0.0.1 8080");  // this machine only, unless told
    EXPECT_EQ(at("0"), "127.0.0.1 0");
    EXPECT_EQ(at("0.0.0.0:65535"), "0.0.0.0 65535");
    EXPECT_EQ(at("localhost:1"), "localhost 1");
    EXPECT_EQ(at("[::1]:80"), "::1 80");
    for (const char* bad : {"", "65536", "99999999999", "http", "-1", ":80", "80:", "host:", "1.5"}) {
        EXPECT_THROW(live::parse_endpoint(bad), std::invalid_argument) << bad;
    }
}

std::string state(live::LiveFeed& feed) { return nlohmann::json::parse(feed.status_json())["state"]; }

TEST(LiveFeed, StopIsRequestedOnceAndEndsAsStopped) {
    live::LiveFeed feed;
    EXPECT_EQ(state(feed), "starting");
    feed.publish({}, nullptr);
    EXPECT_EQ(state(feed), "rendering");
    EXPECT_FALSE(feed.stop_requested());
    feed.request_stop();
    EXPECT_TRUE(feed.stop_requested());
    EXPECT_EQ(state(feed), "stopping");
    feed.finish("out.png");
    const nlohmann::json status = nlohmann::json::parse(feed.status_json());
    EXPECT_EQ(status["state"], "stopped");
    EXPECT_EQ(status["output"], "out.png");

    live::LiveFeed done;
    done.finish("a.png");
    done.request_stop();  // too late: nothing is left to stop
    EXPECT_FALSE(done.stop_requested());
    EXPECT_EQ(state(done), "finished");
}

TEST(LiveFeed, EncodesEachImageOnceAndNumbersThem) {
    live::LiveFeed feed;
    std::uint64_t version = 99;
    EXPECT_EQ(feed.png(version), nullptr);
    EXPECT_EQ(version, 0u);
    feed.publish({}, std::make_shared<const Image>(gradient(4, 4)));
    const auto first = feed.png(version);
    ASSERT_NE(first, nullptr);
    EXPECT_EQ(version, 1u);
    EXPECT_EQ(feed.png(version), first);  // the same bytes, not encoded again
    feed.publish({}, nullptr);             // figures only: the image stays
    EXPECT_EQ(feed.png(version), first);
    feed.publish({}, std::make_shared<const Image>(gradient(8, 2)));
    EXPECT_NE(feed.png(version), first);
    EXPECT_EQ(version, 2u);
    EXPECT_EQ(nlohmann::json::parse(feed.status_json())["image"], 2);
}

TEST(LiveFeed, IsWatchedOnceAPageAsks) {
    live::LiveFeed feed;
    EXPECT_FALSE(feed.watched());
    feed.wait_until_seen(10.0);  // nobody watches: returns at once
    feed.status_json();
    EXPECT_TRUE(feed.watched());
}

TEST(LiveFeed, KeepsOneCurvePerName) {
    live::LiveFeed feed;
    feed.add_error_point("vulkan/path", 0.5, 0.2);
    feed.add_error_point("vulkan/path", 1.0, 0.1);
    feed.add_error_point("cpu/path", 0.7, 0.3);
    const nlohmann::json curves = nlohmann::json::parse(feed.status_json())["curves"];
    ASSERT_EQ(curves.size(), 2u);
    EXPECT_EQ(curves[0]["name"], "vulkan/path");
    EXPECT_EQ(curves[0]["points"], nlohmann::json::parse("[[0.5, 0.2], [1.0, 0.1]]"));
    EXPECT_EQ(curves[1]["points"].size(), 1u);
}

// A watcher sees every pass in order and can end the render after one.
TEST(RenderPlan, AWatcherStopsTheRenderAfterAPass) {
    const Scene scene = test::load_at_size(test::source_dir() / "scenes" / "gallery" / "k_room.json", 16, 12);
    auto backend = make_cpu_backend(1);
    RenderPlan plan;
    plan.samples = 64;
    std::vector<std::uint32_t> seen;
    plan.after_pass = [&](const PassView& view) {
        seen.push_back(view.samples);
        EXPECT_EQ(view.target, 64u);
        EXPECT_EQ(total_rays(view.total) > 0, true);
        return view.samples < 4;
    };
    const RenderOutcome out = render_scene(scene, *backend, plan);
    EXPECT_EQ(seen, (std::vector<std::uint32_t>{1, 2, 4}));
    EXPECT_EQ(out.stats.samples_per_pixel, 4u);
    EXPECT_TRUE(out.stats.stopped_by_request);
    EXPECT_FALSE(out.stats.stopped_by_time);
    EXPECT_EQ(total_rays(out.sums), out.stats.rays());
}

TEST(AtomicWrite, ReplacesWholeOrNotAtAll) {
    const fs::path dir = test::temp_dir("live_atomic");
    const fs::path file = dir / "out.txt";
    std::ofstream(file) << "old";
    EXPECT_THROW(app::write_atomically(file,
                                       [](const fs::path& temporary) {
                                           std::ofstream(temporary) << "half";
                                           throw std::runtime_error("disk full");
                                       }),
                 std::runtime_error);
    std::ifstream kept(file);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "old");
    app::write_atomically(file, [](const fs::path& temporary) {
        EXPECT_EQ(temporary.extension(), ".txt");  // the format is read from it
        std::ofstream(temporary) << "new";
    });
    std::ifstream replaced(file);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(replaced), {}), "new");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // no temporary left
}

}  // namespace
