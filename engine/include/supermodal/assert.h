// SPDX-License-Identifier: MIT
// Programmer-error checks (stale handles, invalid Defs, mutation while stepping). On unless the engine
// is built as Release; the host may install its own handler.
#pragma once

#include "supermodal/api.h"

namespace supermodal
{

/// Called when an engine assertion fails. Return true to abort, false to continue (the call then
/// refuses its work: queries return zeros, creates return a null Entity).
using AssertHandler = bool (*)(const char* condition, const char* message, const char* file, int line);

/// Installs a handler (nullptr restores the default, which prints to stderr and aborts). Returns the
/// previous one. Not thread-safe: set it once at start-up.
SM_API AssertHandler set_assert_handler(AssertHandler handler);

/// True when the engine was built with assertions on.
[[nodiscard]] SM_API bool asserts_enabled();

} // namespace supermodal
