// SPDX-License-Identifier: MIT
// The version: the CMake project's (compile definitions SM_EXPECTED_*), the generated header's macros
// and what the libraries return at run time are one.
#include "supermodal/supermodal.h"
#include "supermodal/version.h"

#include <gtest/gtest.h>
#include <string>

TEST(Version, LibraryReturnsTheCMakeVersion)
{
    EXPECT_EQ(std::string(supermodal::version()), SM_EXPECTED_VERSION);
}

TEST(Version, CApiReturnsTheCMakeVersion)
{
    EXPECT_EQ(std::string(sm_version()), SM_EXPECTED_VERSION);
    EXPECT_STREQ(sm_version(), supermodal::version());
}

TEST(Version, HeaderMacrosMatchTheCMakeVersion)
{
    EXPECT_EQ(std::string(SM_VERSION_STRING), SM_EXPECTED_VERSION);
    EXPECT_EQ(SM_VERSION_MAJOR, SM_EXPECTED_MAJOR);
    EXPECT_EQ(SM_VERSION_MINOR, SM_EXPECTED_MINOR);
    EXPECT_EQ(SM_VERSION_PATCH, SM_EXPECTED_PATCH);
    EXPECT_EQ(std::to_string(SM_VERSION_MAJOR) + "." + std::to_string(SM_VERSION_MINOR) + "." +
                  std::to_string(SM_VERSION_PATCH),
              SM_VERSION_STRING);
}
