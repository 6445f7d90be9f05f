// Progress before the first pass (host/app/preparation_progress.hpp): nothing for a
// scene ready within kShowAfter seconds; after that the step under way, once per step
// on a plain stream, rewritten in place on a terminal. Driven by poll() with set
// times, so the test does not depend on how busy the machine is.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "app/preparation_progress.hpp"

namespace vkrt {
namespace {

using Clock = PreparationProgress::Clock;

std::string contents(std::FILE* f) {
    std::fflush(f);
    std::rewind(f);
    std::string text;
    for (int c; (c = std::fgetc(f)) != EOF;) text += char(c);
    return text;
}

TEST(PreparationProgress, QuickPreparationShowsNothing) {
    std::FILE* out = std::tmpfile();
    {
        PreparationProgress p(true, out, false, false);
        const Clock::time_point start = Clock::now();
        p.step("loading a.gltf");
        p.poll(start + std::chrono::milliseconds(1900));
        p.step("setting up the vulkan backend");
        p.poll(start + std::chrono::milliseconds(1950));
        p.done();
    }
    EXPECT_EQ(contents(out), "");
    std::fclose(out);
}

TEST(PreparationProgress, ALongOneShowsEachStepOnceOnAPlainStream) {
    std::FILE* out = std::tmpfile();
    {
        PreparationProgress p(true, out, false, false);
        const Clock::time_point start = Clock::now();
        p.step("loading a.gltf");
        p.poll(start + std::chrono::milliseconds(2500));
        p.poll(start + std::chrono::milliseconds(3000));
        p.step("setting up the vulkan backend (pipeline, uploads)");
        p.poll(start + std::chrono::milliseconds(4000));
        p.done();
        p.poll(start + std::chrono::milliseconds(9000));  // after done: nothing
    }
    const std::string text = contents(out);
    EXPECT_NE(text.find("preparing: loading a.gltf (2.5 s so far)\n"), std::string::npos) << text;
    EXPECT_NE(text.find("preparing: setting up the vulkan backend (pipeline, uploads) (4.0 s so far)\n"),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find("loading a.gltf", text.find("loading a.gltf") + 1), std::string::npos) << "shown twice: " << text;
    std::fclose(out);
}

TEST(PreparationProgress, OnATerminalOneLineIsRewrittenAndEnded) {
    std::FILE* out = std::tmpfile();
    {
        PreparationProgress p(true, out, true, false);
        const Clock::time_point start = Clock::now();
        p.step("flattening the scene");
        p.poll(start + std::chrono::milliseconds(2100));
        p.poll(start + std::chrono::milliseconds(2200));  // within half a second: not redrawn
        p.poll(start + std::chrono::milliseconds(3100));
        p.done();
    }
    const std::string text = contents(out);
    EXPECT_EQ(text.rfind("\rpreparing: flattening the scene, 2 s so far", 0), 0u) << text;
    EXPECT_NE(text.find("\rpreparing: flattening the scene, 3 s so far"), std::string::npos) << text;
    EXPECT_EQ(text.back(), '\n');
    EXPECT_EQ(text.find('\n'), text.size() - 1) << "one line: " << text;
    std::fclose(out);
}

TEST(PreparationProgress, QuietShowsNothing) {
    std::FILE* out = std::tmpfile();
    {
        PreparationProgress p(false, out, true);
        p.step("loading a.gltf");
        p.poll(Clock::now() + std::chrono::seconds(10));
    }
    EXPECT_EQ(contents(out), "");
    std::fclose(out);
}

}  // namespace
}  // namespace vkrt
