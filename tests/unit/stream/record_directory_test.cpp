// SPDX-License-Identifier: Apache-2.0
// RecordDirectory: finishing, crash leftovers, retention and the figures, on a store in memory; and the real
// directory store on a temporary folder.
#include "stream/record_directory.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "memory_segment_store.h"
#include "stream/directory_segment_store.h"

namespace overlayd {
namespace {

using std::chrono::seconds;

const WallClock::time_point kNow = WallClock::from_time_t(1795791420); // 2026-11-27 14:57:00 UTC

TEST(RecordDirectory, AFinishedSegmentTakesItsFinalName)
{
    MemorySegmentStore store;
    RecordDirectory directory(store, RecordContainer::Mp4, {});
    const std::string partial = directory.nextPartialName(kNow);
    EXPECT_EQ(partial, "20261127T145700Z.mp4.partial");
    store.files[partial] = 1000;
    ASSERT_TRUE(directory.finish(partial, kNow + seconds(2)));
    EXPECT_EQ(store.files, (std::map<std::string, uint64_t>{{"20261127T145700Z.mp4", 1000}}));
    EXPECT_EQ(directory.figures().segments, 1u);
    EXPECT_EQ(directory.figures().bytes, 1000u);
    EXPECT_EQ(directory.figures().oldest, "20261127T145700Z.mp4");
    EXPECT_EQ(directory.largestSegmentBytes(), 1000u);
}

TEST(RecordDirectory, ASecondSegmentInTheSameSecondGetsARepeatNumber)
{
    MemorySegmentStore store;
    store.files["20261127T145700Z.mp4"] = 10;
    store.files["20261127T145700Z-1.mp4.partial"] = 10;
    RecordDirectory directory(store, RecordContainer::Mp4, {});
    EXPECT_EQ(directory.nextPartialName(kNow), "20261127T145700Z-2.mp4.partial");
    // Another container's names do not collide.
    RecordDirectory matroska(store, RecordContainer::Matroska, {});
    EXPECT_EQ(matroska.nextPartialName(kNow), "20261127T145700Z.mkv.partial");
}

TEST(RecordDirectory, AnEmptySegmentIsRemovedNotKept)
{
    MemorySegmentStore store;
    RecordDirectory directory(store, RecordContainer::Mp4, {});
    store.files["20261127T145700Z.mp4.partial"] = 0;
    ASSERT_TRUE(directory.finish("20261127T145700Z.mp4.partial", kNow));
    EXPECT_TRUE(store.files.empty());
    EXPECT_FALSE(directory.finish("20261127T145700Z.mp4.partial", kNow)); // gone
    EXPECT_FALSE(directory.finish("notes.txt", kNow));
}

TEST(RecordDirectory, RecoveryFinishesWhatACrashLeftAndLeavesOtherFiles)
{
    MemorySegmentStore store;
    store.files["20261127T145500Z.mp4"] = 100;
    store.files["20261127T145600Z.mp4.partial"] = 50; // killed mid-segment: readable up to its last fragment
    store.files["20261127T145700Z.mp4.partial"] = 0;  // killed before its first fragment
    store.files["notes.txt.partial"] = 7;
    store.files["20261127T145800Z.mkv.partial"] = 9; // another container's recording
    RecordDirectory directory(store, RecordContainer::Mp4, {});
    ASSERT_TRUE(directory.recover(kNow));
    EXPECT_EQ(store.files, (std::map<std::string, uint64_t>{{"20261127T145500Z.mp4", 100},
                                                            {"20261127T145600Z.mp4", 50},
                                                            {"20261127T145800Z.mkv.partial", 9},
                                                            {"notes.txt.partial", 7}}));
    EXPECT_EQ(directory.figures().recovered, 1u);
    EXPECT_EQ(directory.figures().segments, 2u);
    EXPECT_EQ(directory.figures().oldest, "20261127T145500Z.mp4");
}

TEST(RecordDirectory, RetentionDeletesTheOldestAndCountsThem)
{
    MemorySegmentStore store;
    RecordDirectory directory(store, RecordContainer::Mp4, {250, {}});
    for (int i = 0; i < 4; ++i) {
        const std::string partial = directory.nextPartialName(kNow + seconds(2 * i));
        store.files[partial] = 100;
        ASSERT_TRUE(directory.finish(partial, kNow + seconds(2 * i + 2)));
    }
    EXPECT_EQ(store.files,
              (std::map<std::string, uint64_t>{{"20261127T145704Z.mp4", 100}, {"20261127T145706Z.mp4", 100}}));
    EXPECT_EQ(directory.figures().deleted, 2u);
    EXPECT_EQ(directory.figures().oldest, "20261127T145704Z.mp4");
    // The segment being written counts: with 100 bytes in it, only one finished segment fits.
    ASSERT_TRUE(directory.prune(kNow + seconds(9), 100));
    EXPECT_EQ(store.files.size(), 1u);
    EXPECT_EQ(directory.figures().deleted, 3u);
}

TEST(RecordDirectory, AFileThatWillNotGoDoesNotStopTheRest)
{
    MemorySegmentStore store;
    store.files["20261127T145500Z.mp4"] = 100;
    store.files["20261127T145600Z.mp4"] = 100;
    store.files["20261127T145700Z.mp4"] = 100;
    store.stuck.insert("20261127T145500Z.mp4");
    RecordDirectory directory(store, RecordContainer::Mp4, {100, {}});
    EXPECT_FALSE(directory.prune(kNow, 0));
    EXPECT_EQ(store.files.size(), 2u); // the stuck oldest, and the newest
    EXPECT_TRUE(store.files.count("20261127T145700Z.mp4"));
    EXPECT_EQ(directory.figures().deleted, 1u);
    EXPECT_EQ(directory.figures().segments, 2u);
}

class RealDirectory : public ::testing::Test
{
protected:
    void SetUp() override
    {
        path_ =
            std::filesystem::temp_directory_path() / ("overlayd-record-" + std::to_string(getpid()) + "-" +
                                                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    void TearDown() override { std::filesystem::remove_all(path_); }
    void write(const std::string &name, size_t bytes) { std::ofstream(path_ / name) << std::string(bytes, 'x'); }

    std::filesystem::path path_;
};

TEST_F(RealDirectory, FinishesRenamesAndPrunesOnDisk)
{
    DirectorySegmentStore store(path_.string() + "/");
    ASSERT_TRUE(store.checkWritable());
    RecordDirectory directory(store, RecordContainer::Matroska, {150, {}});
    write("20261127T145600Z.mkv", 100);
    std::filesystem::create_directory(path_ / "20261127T145500Z.mkv"); // a folder named like one: not a segment
    std::filesystem::create_symlink(path_ / "20261127T145600Z.mkv", path_ / "20261127T145400Z.mkv");
    const std::string partial = directory.nextPartialName(kNow);
    write(partial, 100);
    ASSERT_TRUE(directory.finish(partial, kNow));
    EXPECT_FALSE(std::filesystem::exists(path_ / "20261127T145600Z.mkv"));
    EXPECT_EQ(std::filesystem::file_size(path_ / "20261127T145700Z.mkv"), 100u);
    EXPECT_TRUE(std::filesystem::is_directory(path_ / "20261127T145500Z.mkv"));
    EXPECT_TRUE(std::filesystem::is_symlink(path_ / "20261127T145400Z.mkv"));
    EXPECT_EQ(directory.figures().segments, 1u);
    const auto free = store.freeBytes();
    ASSERT_TRUE(free);
    EXPECT_GT(*free, 0u);
}

TEST_F(RealDirectory, WritableChecksNameTheDirectory)
{
    const auto missing = DirectorySegmentStore((path_ / "nope").string()).checkWritable();
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().message, "'" + (path_ / "nope").string() + "' does not exist");
    write("file", 1);
    const auto file = DirectorySegmentStore((path_ / "file").string()).checkWritable();
    ASSERT_FALSE(file);
    EXPECT_EQ(file.error().message, "'" + (path_ / "file").string() + "' is not a directory");
    // Nothing of the probe stays behind.
    ASSERT_TRUE(DirectorySegmentStore(path_.string()).checkWritable());
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(path_), {}), 1);
}

} // namespace
} // namespace overlayd
