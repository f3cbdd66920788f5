// Results sent between MPI ranks come back bit for bit.
#include "dist/bytes.h"
#include "dist/job_hand_out.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

namespace vkray::dist {
namespace {

TEST(Bytes, NumbersAndStringsComeBackBitForBit) {
    const double values[] = {0.1,
                             -0.0,
                             1e-310,
                             std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::quiet_NaN(),
                             6.02214076e23};
    const std::string text("tab\there, a NUL \0 and more", 26);
    ByteWriter writer;
    for (double v : values) writer << v;
    writer << text << std::size_t(12345678901234) << std::int32_t(-7) << true;
    ByteReader reader(writer.bytes());
    for (double v : values) {
        double back = 0;
        reader >> back;
        EXPECT_EQ(std::bit_cast<std::uint64_t>(back), std::bit_cast<std::uint64_t>(v));
    }
    std::string textBack;
    std::size_t count = 0;
    std::int32_t negative = 0;
    bool flag = false;
    reader >> textBack >> count >> negative >> flag;
    EXPECT_EQ(textBack, text);
    EXPECT_EQ(count, 12345678901234u);
    EXPECT_EQ(negative, -7);
    EXPECT_TRUE(flag);
    EXPECT_TRUE(reader.atEnd());
}

TEST(Bytes, AResultCutShortIsAnError) {
    ByteWriter writer;
    writer << std::string("twelve bytes");
    const std::string cut = writer.bytes().substr(0, writer.bytes().size() - 1);
    ByteReader reader(cut);
    std::string text;
    EXPECT_THROW(reader >> text, Error);
}

TEST(JobHandOut, OneRankRunsEveryJobInOrder) {
    std::vector<std::size_t> ran;
    const std::vector<std::string> results =
        runJobsAcrossRanks(World::current(), 5, [&](std::size_t job) {
            ran.push_back(job);
            return std::string(job, 'x');
        });
    EXPECT_EQ(ran, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
    ASSERT_EQ(results.size(), 5u);
    for (std::size_t job = 0; job < 5; ++job) EXPECT_EQ(results[job], std::string(job, 'x'));
}

}  // namespace
}  // namespace vkray::dist
