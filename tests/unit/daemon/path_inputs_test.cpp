// SPDX-License-Identifier: Apache-2.0
// PathInputs on real files: the file's points replace the annotation's through SceneControl; a malformed version is
// refused naming its line and the points shown stay; a missing file is an empty path; a rebuilt renderer keeps them.
#include "control/path_inputs.h"

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "fakes.h"
#include "inputs/point_list.h"

namespace overlayd {
namespace {

struct PathInputsTest : test::RecordingSceneTest {
    // One folder per test and process: CTest runs the tests of this file in parallel.
    std::filesystem::path dir =
        std::filesystem::temp_directory_path() /
        (std::string("overlayd-") + ::testing::UnitTest::GetInstance()->current_test_info()->name() + "-" +
         std::to_string(::getpid()));
    std::string file = (dir / "route.txt").string();
    std::vector<std::string> logged;
    Logger logger{[this](std::string_view line) { logged.emplace_back(line); }, true};
    PathInputs paths{logger, control};

    void SetUp() override
    {
        std::filesystem::create_directories(dir);
        OverlayScene scene;
        scene.annotations.push_back({"route", "world", {}, PolylineShape{{{0, 0, 0}, {1, 0, 0}}, false}});
        control.load(scene, CameraSpec{});
        attachStream();
    }
    void TearDown() override { std::filesystem::remove_all(dir); }
    void write(const std::string &text) { std::ofstream(file) << text; }
    const std::vector<glm::dvec3> &shown() const
    {
        return std::get<PolylineShape>(control.scene().annotations[0].shape).points;
    }
};

TEST_F(PathInputsTest, TheFilesPointsReplaceTheAnnotationsAndSurviveARebuild)
{
    write("0 0 0\n2 3 0\n4, 5, 0.5\n");
    ASSERT_TRUE(paths.configure({{"route", file}}));
    paths.showAll();
    const std::vector<glm::dvec3> expected{{0, 0, 0}, {2, 3, 0}, {4, 5, 0.5}};
    EXPECT_EQ(shown(), expected);
    ASSERT_EQ(renderer->worldPoints.size(), 1u);
    EXPECT_EQ(renderer->worldPoints[0].second, expected);
    EXPECT_EQ(paths.readings()[0].points, 3u);
    EXPECT_TRUE(paths.readings()[0].error.empty());
    attachStream(); // a new stream: the renderer is built from the scene, which holds the file's points
    EXPECT_EQ(shown(), expected);
}

TEST_F(PathInputsTest, AMalformedVersionIsRefusedAndThePointsStay)
{
    write("0 0 0\n2 3 0\n");
    ASSERT_TRUE(paths.configure({{"route", file}}));
    paths.showAll();
    write("0 0 0\n2 3\n");
    paths.showAll();
    EXPECT_EQ(shown(), (std::vector<glm::dvec3>{{0, 0, 0}, {2, 3, 0}}));
    EXPECT_EQ(renderer->worldPoints.size(), 1u);
    EXPECT_NE(paths.readings()[0].error.find(file + ":2: 2 number(s)"), std::string::npos) << paths.readings()[0].error;
    ASSERT_FALSE(logged.empty());
    EXPECT_NE(logged.back().find("the points shown stay"), std::string::npos) << logged.back();

    std::filesystem::remove(file); // no plan: nothing drawn
    paths.showAll();
    EXPECT_TRUE(shown().empty());
    EXPECT_TRUE(paths.readings()[0].error.empty());
}

TEST_F(PathInputsTest, AFileOverTheByteLimitIsRefused)
{
    write("0 0 0\n");
    ASSERT_TRUE(paths.configure({{"route", file}}));
    paths.showAll();
    write(std::string(kMaxPathFileBytes + 1, '#'));
    paths.showAll();
    EXPECT_EQ(shown().size(), 1u);
    EXPECT_NE(paths.readings()[0].error.find("more than"), std::string::npos) << paths.readings()[0].error;
}

TEST_F(PathInputsTest, AFolderThatCannotBeWatchedRefusesTheWholeConfigure)
{
    ASSERT_TRUE(paths.configure({{"route", file}}));
    const Status refused = paths.configure({{"route", "/nonexistent-overlayd-folder/route.txt"}});
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("input.path 'route'"), std::string::npos) << refused.error().message;
    EXPECT_EQ(paths.readings()[0].file, file) << "the previous watch stays";
}

} // namespace
} // namespace overlayd
