// Replays every kept fuzz input (tests/fuzz/regressions: findings once fixed; tests/fuzz/corpus: the
// seeds) through the fuzz target's own case, so a fixed crash or hang that returns fails ctest (a hang
// by the test's timeout).
#include "fuzz/fuzz_case.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

namespace fs = std::filesystem;
namespace fz = supermodal::fuzz;

namespace
{
std::string read_text(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

int replay_folder(const char* folder)
{
    int count = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(fs::path(SM_SOURCE_DIR) / folder)) {
        if (!e.is_regular_file())
            continue;
        EXPECT_NE(fz::run_scene_case(read_text(e.path())), fz::Verdict::BadError) << e.path();
        ++count;
    }
    return count;
}
} // namespace

TEST(FuzzReplay, FixedFindingsRunClean)
{
    EXPECT_GE(replay_folder("tests/fuzz/regressions"), 1);
}

TEST(FuzzReplay, SeedCorpusRunsClean)
{
    EXPECT_GE(replay_folder("tests/fuzz/corpus"), 1);
}

TEST(FuzzReplay, TheHugeBodyFindingLoadsAndSteps)
{
    // A 1e60 m ellipsoid among the pile: valid input, so it must load and step (it used to stall one
    // step for minutes inside libccd's MPR).
    const std::string text =
        read_text(fs::path(SM_SOURCE_DIR) / "tests/fuzz/regressions/hang_huge_radius.json");
    EXPECT_EQ(fz::run_scene_case(text), fz::Verdict::Stepped);
}
