// SPDX-License-Identifier: MIT
// The library's version: compiled in from the generated supermodal/version.h.
#include "supermodal/version.h"

namespace supermodal
{

const char* version()
{
    return SM_VERSION_STRING;
}

} // namespace supermodal
