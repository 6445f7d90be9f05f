// vkrt stack (image/stack.hpp): the mean of K images and the variance of that mean
// from their spread, exactly; its refusals; and the file it writes, whose variance
// layer and degrees of freedom compare --test reads.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "image/image_files.hpp"
#include "image/stack.hpp"
#include "test_support.hpp"
#include "uniform_image.hpp"

namespace vkrt {
namespace {

using test::uniform_image;

// Values 1, 2, 3, 4: mean 2.5, unbiased variance 5/3, of the mean 5/12.
TEST(Stack, MeanAndVarianceOfTheMean) {
    std::vector<Image> images;
    for (float v : {1.0f, 2.0f, 3.0f, 4.0f}) images.push_back(uniform_image(2, 1, v));
    images[2].rgb[5] = 7.0f;  // pixel 1, blue: 1, 2, 7, 4: mean 3.5, variance 7, of the mean 1.75
    const StackedImage s = stack_images(images);
    EXPECT_EQ(s.dof, 3.0);
    EXPECT_EQ(s.mean.rgb[0], 2.5f);
    EXPECT_FLOAT_EQ(s.variance.rgb[0], 5.0f / 12.0f);
    EXPECT_EQ(s.mean.rgb[5], 3.5f);
    EXPECT_FLOAT_EQ(s.variance.rgb[5], 1.75f);
    // Equal images: variance 0.
    EXPECT_EQ(stack_images({uniform_image(1, 1, 0.3f), uniform_image(1, 1, 0.3f)}).variance.rgb[0], 0.0f);
}

TEST(Stack, RefusesOneImageAndImagesOfTwoSizes) {
    try {
        stack_images({uniform_image(2, 2, 1.0f)});
        ADD_FAILURE() << "one image has no spread";
    } catch (const ImageError& e) {
        EXPECT_NE(std::string(e.what()).find("two images or more"), std::string::npos) << e.what();
    }
    try {
        stack_images({uniform_image(2, 2, 1.0f), uniform_image(2, 2, 1.0f), uniform_image(3, 2, 1.0f)});
        ADD_FAILURE() << "sizes differ";
    } catch (const ImageError& e) {
        EXPECT_NE(std::string(e.what()).find("image 3 is 3x2, the first 2x2"), std::string::npos) << e.what();
    }
}

// The command writes the mean with its variance layer and degrees of freedom, and
// compare --test reads them: a candidate whose variance is its own against the
// stack of three images.
TEST(Stack, CommandWritesWhatCompareTestReads) {
    const std::filesystem::path dir = test::temp_dir("stack_cli");
    const auto quoted = [&](const std::string& name) { return test::shell_quote((dir / name).string()); };
    for (int k = 0; k < 3; ++k) write_image(uniform_image(6, 6, 0.5f + 0.01f * float(k)), dir / ("run" + std::to_string(k) + ".exr"));
    const test::ProgramRun run =
        test::run_vkrt("stack " + quoted("run0.exr") + " " + quoted("run1.exr") + " " + quoted("run2.exr") + " -o " +
                           quoted("stack.exr"),
                       dir);
    ASSERT_EQ(run.code, 0) << run.stderr_text;
    std::string error;
    const std::unique_ptr<ImageFileReader> in = image_files().open((dir / "stack.exr").string(), error);
    ASSERT_TRUE(in) << error;
    EXPECT_EQ(in->spec().string_or(kVarianceDofAttribute), "2");
    std::vector<float> values(in->spec().channels.size() * 36);
    ASSERT_TRUE(in->read_floats(values.data()));
    EXPECT_FLOAT_EQ(values[0], 0.51f);
    EXPECT_NEAR(values[3], 0.0001 / 3.0, 1e-9);  // variance.R: (0.01^2 + 0 + 0.01^2) / 2 / 3

    Image candidate = uniform_image(6, 6, 0.51f);
    write_layered_exr(candidate, {ImageLayer{"variance", {"R", "G", "B"}, std::vector<float>(108, 1e-4f)}},
                      dir / "candidate.exr");
    const test::ProgramRun test_run = test::run_vkrt("compare " + quoted("candidate.exr") + " " + quoted("stack.exr") + " --test", dir);
    EXPECT_EQ(test_run.code, 0) << test_run.stderr_text;
    std::ifstream out(dir / "stdout.txt");
    const std::string text((std::istreambuf_iterator<char>(out)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("A's variance its own, B's of 2 degrees of freedom"), std::string::npos) << text;

    // A variance whose degrees of freedom are not a number above 0 is unusable: exit 2.
    for (const char* dof : {"abc", "0", "-3"}) {
        write_layered_exr(candidate, {ImageLayer{"variance", {"R", "G", "B"}, std::vector<float>(108, 1e-4f)}},
                          dir / "bad_dof.exr", {{kVarianceDofAttribute, dof}});
        const test::ProgramRun bad =
            test::run_vkrt("compare " + quoted("bad_dof.exr") + " " + quoted("stack.exr") + " --test", dir);
        EXPECT_EQ(bad.code, 2) << dof;
        EXPECT_NE(bad.stderr_text.find(std::string("vkrt:variance_dof attribute, '") + dof + "', is not a number above 0"),
                  std::string::npos)
            << bad.stderr_text;
    }

    test::expect_one_error(test::run_vkrt("stack " + quoted("run0.exr") + " -o " + quoted("one.exr"), dir),
                           {"two images or more"});
    test::expect_one_error(test::run_vkrt("stack " + quoted("run0.exr") + " " + quoted("run1.exr") + " -o " + quoted("s.png"), dir),
                           {"s.png", "give -o a name ending in .exr"});
}

}  // namespace
}  // namespace vkrt
