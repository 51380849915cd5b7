// SPDX-License-Identifier: MIT
#include "core/assert.h"

#include <cstdio>
#include <cstdlib>

namespace supermodal
{
namespace
{
bool default_handler(const char* condition, const char* message, const char* file, int line)
{
    std::fprintf(stderr, "supermodal: assertion failed: %s (%s) at %s:%d\n", message, condition, file, line);
    return true;
}
// The one mutable global: a host-installed hook, set at start-up.
AssertHandler g_handler = &default_handler;
} // namespace

AssertHandler set_assert_handler(AssertHandler handler)
{
    AssertHandler previous = g_handler;
    g_handler = handler ? handler : &default_handler;
    return previous;
}

bool asserts_enabled()
{
#ifdef SM_ENABLE_ASSERT
    return true;
#else
    return false;
#endif
}

namespace detail
{
void assert_failed(const char* condition, const char* message, const char* file, int line)
{
    if (g_handler(condition, message, file, line))
        std::abort();
}
} // namespace detail
} // namespace supermodal
