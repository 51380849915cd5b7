// SPDX-License-Identifier: MIT
// Everything public in C++, in one include. The plain-C API is supermodal/supermodal.h (docs/c_api.md).
#pragma once

#include "supermodal/assert.h"
#include "supermodal/body.h"
#include "supermodal/constraint.h"
#include "supermodal/contact.h"
#include "supermodal/entity.h"
#include "supermodal/fault.h"
#include "supermodal/geometry.h"
#include "supermodal/hierarchy.h"
#include "supermodal/math.h"
#include "supermodal/modal.h"
#include "supermodal/result.h"
#include "supermodal/scene.h"
#include "supermodal/shape.h"
#include "supermodal/tasks.h"
#include "supermodal/world.h"
