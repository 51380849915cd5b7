// SPDX-License-Identifier: MIT
// SM_ASSERT(cond, "message"): on when SM_ENABLE_ASSERT is defined (all but Release builds).
#pragma once

#include "supermodal/assert.h"

namespace supermodal::detail
{
/// Reports a failed assertion through the installed handler; aborts if it says so.
void assert_failed(const char* condition, const char* message, const char* file, int line);
} // namespace supermodal::detail

#ifdef SM_ENABLE_ASSERT
#define SM_ASSERT(cond, msg)                                                                                 \
    do {                                                                                                     \
        if (!(cond))                                                                                         \
            ::supermodal::detail::assert_failed(#cond, msg, __FILE__, __LINE__);                             \
    } while (false)
#else
#define SM_ASSERT(cond, msg)                                                                                 \
    do {                                                                                                     \
        (void)sizeof(cond);                                                                                  \
    } while (false)
#endif
